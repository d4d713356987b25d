// SPDX-License-Identifier: MIT
// 2D channel [0,2]x[0,1], structured quadrilaterals (32 x 16);
// groups "bottom" (1), "right" (2), "top" (3), "left" (4), "domain" (5).
Point(1) = {0, 0, 0}; Point(2) = {2, 0, 0}; Point(3) = {2, 1, 0}; Point(4) = {0, 1, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 3} = 33;
Transfinite Curve{2, 4} = 17;
Transfinite Surface{1};
Recombine Surface{1};
Physical Curve("bottom", 1) = {1};
Physical Curve("right", 2) = {2};
Physical Curve("top", 3) = {3};
Physical Curve("left", 4) = {4};
Physical Surface("domain", 5) = {1};
