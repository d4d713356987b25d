// SPDX-License-Identifier: MIT
// 3D box [-1,1]^3 minus a sphere of radius 0.4 at the origin, tetrahedra;
// groups "box" (1, the six outer faces), "sphere" (2), "volume" (3).
SetFactory("OpenCASCADE");
Box(1) = {-1, -1, -1, 2, 2, 2};
Sphere(2) = {0, 0, 0, 0.4};
BooleanDifference(3) = { Volume{1}; Delete; }{ Volume{2}; Delete; };
eps = 1e-3;
sphere() = Surface In BoundingBox{-0.4 - eps, -0.4 - eps, -0.4 - eps, 0.4 + eps, 0.4 + eps, 0.4 + eps};
all() = Surface{:};
box() = all();
box() -= sphere();
Physical Surface("box", 1) = box();
Physical Surface("sphere", 2) = sphere();
Physical Volume("volume", 3) = {3};
Mesh.MeshSizeMax = 0.3;
Mesh.MeshSizeMin = 0.1;
Mesh.MeshSizeFromCurvature = 12;
