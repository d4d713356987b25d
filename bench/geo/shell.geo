// SPDX-License-Identifier: MIT
// Paper 000 §4.2 / §5.2: the shell between the spheres r = 1 and r = 21 (centre 0), linear
// tetrahedra. The element size grows from lc on the inner sphere to 10 lc on the outer one:
// linearly with the radius (grading = 1), or as the power `grading` of (r − 1)/20, which
// keeps the cells finer further out. scripts/make-bench-meshes sets lc and grading.
// Groups: "inner" (1), "outer" (2), "domain" (3).
SetFactory("OpenCASCADE");
If (!Exists(lc)) lc = 0.4; EndIf
If (!Exists(grading)) grading = 1; EndIf
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
If (grading == 1)
  Field[1].F = Sprintf("%.17g * (1 + 0.45 * (Sqrt(x * x + y * y + z * z) - 1))", lc);
Else
  Field[1].F = Sprintf("%.17g * (1 + 9 * ((Sqrt(x * x + y * y + z * z) - 1) / 20)^%.17g)", lc, grading);
EndIf
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
