// SPDX-License-Identifier: MIT
// Paper 000 §5.3 in 2D: a boundary-layer mesh around the unit circle (centre 0) inside the
// circle of radius 10. Straight-sided linear triangles (the case elevates them to order 3).
// First layer h_first = 1e-5 thick, growth 1.3, as many layers as reach the wall's tangential
// size h_wall (Gmsh's BoundaryLayer field, split into triangles). scripts/bench-gmsh-ho sets
// h_first to 1e-3 and 1e-4 too.
// Groups: "wall" (1), "farfield" (2), "domain" (3).
If (!Exists(h_wall)) h_wall = 0.2; EndIf
If (!Exists(h_far)) h_far = 2.0; EndIf
If (!Exists(h_first)) h_first = 1e-5; EndIf
R = 10;
Point(1) = {0, 0, 0, h_wall};
Point(2) = {1, 0, 0, h_wall}; Point(3) = {0, 1, 0, h_wall};
Point(4) = {-1, 0, 0, h_wall}; Point(5) = {0, -1, 0, h_wall};
Point(6) = {R, 0, 0, h_far}; Point(7) = {0, R, 0, h_far};
Point(8) = {-R, 0, 0, h_far}; Point(9) = {0, -R, 0, h_far};
Circle(1) = {2, 1, 3}; Circle(2) = {3, 1, 4}; Circle(3) = {4, 1, 5}; Circle(4) = {5, 1, 2};
Circle(5) = {6, 1, 7}; Circle(6) = {7, 1, 8}; Circle(7) = {8, 1, 9}; Circle(8) = {9, 1, 6};
Curve Loop(1) = {5, 6, 7, 8};
Curve Loop(2) = {1, 2, 3, 4};
Plane Surface(1) = {1, 2};
Physical Curve("wall", 1) = {1, 2, 3, 4};
Physical Curve("farfield", 2) = {5, 6, 7, 8};
Physical Surface("domain", 3) = {1};
// Layers h_first * 1.3^k for k = 0 .. n-1 with h_first * 1.3^(n-1) about h_wall.
n = Ceil(Log(h_wall / h_first) / Log(1.3)) + 1;
Field[1] = BoundaryLayer;
Field[1].CurvesList = {1, 2, 3, 4};
Field[1].Size = h_first;
Field[1].Ratio = 1.3;
Field[1].Thickness = h_first * (1.3^n - 1) / 0.3;
Field[1].SizeFar = h_wall;
Field[1].Quads = 0;
BoundaryLayer Field = 1;
