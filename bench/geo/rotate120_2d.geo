// SPDX-License-Identifier: MIT
// Paper 000 §5.1-like: a disk of radius 5 with three holes of radius 0.5 whose centres lie
// on a circle of radius 1.5 around the common centre (0, 0), 120° apart, so that a 120°
// rotation maps the holes onto each other. Linear triangles, ~1300 nodes.
// Groups: "inner" (1, the three hole circles), "outer" (2), "domain" (3).
If (!Exists(h_in)) h_in = 0.14; EndIf
If (!Exists(h_out)) h_out = 0.6; EndIf
If (!Exists(R)) R = 5; EndIf
d = 1.5; r = 0.5;
Point(1) = {0, 0, 0, h_out};
Point(2) = {R, 0, 0, h_out}; Point(3) = {0, R, 0, h_out};
Point(4) = {-R, 0, 0, h_out}; Point(5) = {0, -R, 0, h_out};
Circle(1) = {2, 1, 3}; Circle(2) = {3, 1, 4}; Circle(3) = {4, 1, 5}; Circle(4) = {5, 1, 2};
Curve Loop(1) = {1, 2, 3, 4};
For k In {0 : 2}
  a = Pi / 2 + k * 2 * Pi / 3;
  cx = d * Cos(a); cy = d * Sin(a);
  p = 10 + 10 * k;
  Point(p) = {cx, cy, 0, h_in};
  Point(p + 1) = {cx + r, cy, 0, h_in}; Point(p + 2) = {cx, cy + r, 0, h_in};
  Point(p + 3) = {cx - r, cy, 0, h_in}; Point(p + 4) = {cx, cy - r, 0, h_in};
  Circle(p + 1) = {p + 1, p, p + 2}; Circle(p + 2) = {p + 2, p, p + 3};
  Circle(p + 3) = {p + 3, p, p + 4}; Circle(p + 4) = {p + 4, p, p + 1};
  Curve Loop(2 + k) = {p + 1, p + 2, p + 3, p + 4};
EndFor
Plane Surface(1) = {1, 2, 3, 4};
Physical Curve("inner", 1) = {11, 12, 13, 14, 21, 22, 23, 24, 31, 32, 33, 34};
Physical Curve("outer", 2) = {1, 2, 3, 4};
Physical Surface("domain", 3) = {1};
