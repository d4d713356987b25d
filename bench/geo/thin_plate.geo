// SPDX-License-Identifier: MIT
// A thin plate 0.4 x 0.2 x 0.02 (x, y, z) centred in the unit box [0, 1]^3, as a hole;
// linear tetrahedra. The size is h_plate on the plate and blends linearly to h_box at the
// distance 0.1 from it. h_plate is coarse for a plate 0.02 thick (5 times its thickness,
// one cell across its side faces), as a mesh sized for the plate's length rather than its
// thickness is: the tetrahedra on the side faces and edges are flat (longest edge over
// smallest height up to about 8, against 3 in the rest of the box).
// Groups: "plate" (1), "outer" (2), "domain" (3).
SetFactory("OpenCASCADE");
If (!Exists(h_plate)) h_plate = 0.1; EndIf
If (!Exists(h_box)) h_box = 0.058; EndIf
Box(1) = {0, 0, 0, 1, 1, 1};
Box(2) = {0.3, 0.4, 0.49, 0.4, 0.2, 0.02};
BooleanDifference(3) = { Volume{1}; Delete; }{ Volume{2}; Delete; };
eps = 1e-3;
plate() = Surface In BoundingBox{0.3 - eps, 0.4 - eps, 0.49 - eps, 0.7 + eps, 0.6 + eps, 0.51 + eps};
outer() = Surface{:};
outer() -= plate();
Physical Surface("plate", 1) = plate();
Physical Surface("outer", 2) = outer();
Physical Volume("domain", 3) = {3};
Field[1] = Distance;
Field[1].SurfacesList = {plate()};
Field[2] = MathEval;
Field[2].F = Sprintf("%.17g * (1 - Min(1, F1 / 0.1)) + %.17g * Min(1, F1 / 0.1)", h_plate, h_box);
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
