// SPDX-License-Identifier: MIT
// Paper 000 §5.5-like in 2D: a rotor (a hub circle of radius 1 with five elliptic blades,
// semi-axes 1.7 x 0.25, centred at radius 2.4 and 72° apart, so tips reach r = 4.1)
// inside the circle of radius 8 (centre 0). Linear triangles, refined towards the rotor.
// Groups: "rotor" (1, hub + blade curves), "outer" (2), "domain" (3).
SetFactory("OpenCASCADE");
If (!Exists(h_rotor)) h_rotor = 0.08; EndIf
If (!Exists(h_far)) h_far = 0.6; EndIf
Disk(1) = {0, 0, 0, 8};
Disk(2) = {0, 0, 0, 1};
For k In {0 : 4}
  Disk(3 + k) = {2.4, 0, 0, 1.7, 0.25};
  Rotate {{0, 0, 1}, {0, 0, 0}, k * 2 * Pi / 5} { Surface{3 + k}; }
EndFor
BooleanUnion(10) = { Surface{2}; Delete; }{ Surface{3 : 7}; Delete; };
BooleanDifference(11) = { Surface{1}; Delete; }{ Surface{10}; Delete; };
eps = 1e-3;
rotor() = Curve In BoundingBox{-4.2, -4.2, -eps, 4.2, 4.2, eps};
outer() = Curve{:};
outer() -= rotor();
Physical Curve("rotor", 1) = rotor();
Physical Curve("outer", 2) = outer();
Physical Surface("domain", 3) = {11};
Field[1] = Distance;
Field[1].CurvesList = {rotor()};
Field[1].NumPointsPerCurve = 200;
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = h_rotor;
Field[2].SizeMax = h_far;
Field[2].DistMin = 0;
Field[2].DistMax = 3;
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
