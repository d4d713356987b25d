// SPDX-License-Identifier: MIT
// Paper 000 §4.2 / §5.2: the shell between the spheres r = 1 and r = 21 (centre 0), linear
// tetrahedra. The element size grows linearly with the radius from lc on the inner sphere
// to 10 lc on the outer one. scripts/make-bench-meshes sets lc for each node count.
// Groups: "inner" (1), "outer" (2), "domain" (3).
SetFactory("OpenCASCADE");
If (!Exists(lc)) lc = 0.4; EndIf
Sphere(1) = {0, 0, 0, 21};
Sphere(2) = {0, 0, 0, 1};
BooleanDifference(3) = { Volume{1}; Delete; }{ Volume{2}; Delete; };
eps = 1e-3;
inner() = Surface In BoundingBox{-1 - eps, -1 - eps, -1 - eps, 1 + eps, 1 + eps, 1 + eps};
outer() = Surface{:};
outer() -= inner();
Physical Surface("inner", 1) = inner();
Physical Surface("outer", 2) = outer();
Physical Volume("domain", 3) = {3};
Field[1] = MathEval;
Field[1].F = Sprintf("%.17g * (1 + 0.45 * (Sqrt(x * x + y * y + z * z) - 1))", lc);
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
