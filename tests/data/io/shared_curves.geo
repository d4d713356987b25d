// SPDX-License-Identifier: MIT
// square_hole.geo with curves in two physical groups each: "walls" holds the hole and the
// bottom side, which are also in "hole wall" and "outer"; and the surface in "fluid" and
// "all" (read_fixtures_test.cpp).
SetFactory("OpenCASCADE");
Rectangle(1) = {0, 0, 0, 2, 1};
Disk(2) = {0.6, 0.5, 0, 0.2};
BooleanDifference{ Surface{1}; Delete; }{ Surface{2}; Delete; }
Mesh.MeshSizeMax = 0.35;
Physical Surface("fluid", 10) = {1};
Physical Curve("hole wall", 20) = {5};
Physical Curve("outer", 21) = {6, 7, 8, 9};
Physical Curve("walls", 22) = {5, 6};
Physical Surface("all", 30) = {1};
