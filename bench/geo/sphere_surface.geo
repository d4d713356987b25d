// SPDX-License-Identifier: MIT
// The unit sphere (centre 0) as a surface triangulation of size h; scripts/make-bench-meshes
// extrudes it radially into the boundary layers of bl_sphere_3d. Group: "wall" (1).
SetFactory("OpenCASCADE");
If (!Exists(h)) h = 0.7; EndIf
Sphere(1) = {0, 0, 0, 1};
Physical Surface("wall", 1) = {1};
Mesh.MeshSizeMin = h;
Mesh.MeshSizeMax = h;
Mesh.MeshSizeFromCurvature = 0;
