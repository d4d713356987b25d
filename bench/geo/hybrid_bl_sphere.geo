// SPDX-License-Identifier: MIT
// A hybrid boundary-layer mesh of the CFD kind: the sphere of diameter 1 (centre 0) in the box
// [-B, B]^3. The sphere's surface mesh is extruded along its normals in n_layers layers, the
// first h_first thick, growing by 1.3 (Extrude Layers with Recombine): prisms on its
// triangles, hexahedra on the upper quarter (y > 0, z > 0), whose triangles are recombined
// into quadrilaterals. Tetrahedra fill the rest, with pyramids where they meet the hexahedra's
// top faces. Built-in kernel (the normal extrusion needs it). Groups: "wall" (1), "farfield"
// (2), "domain" (3).
If (!Exists(h_first)) h_first = 5e-4; EndIf
If (!Exists(n_layers)) n_layers = 14; EndIf
If (!Exists(h_wall)) h_wall = 0.075; EndIf
If (!Exists(h_far)) h_far = 0.75; EndIf
If (!Exists(B)) B = 3; EndIf
r = 0.5;
Point(1) = {0, 0, 0, h_wall};
Point(2) = {r, 0, 0, h_wall}; Point(3) = {0, r, 0, h_wall}; Point(4) = {0, 0, r, h_wall};
Point(5) = {-r, 0, 0, h_wall}; Point(6) = {0, -r, 0, h_wall}; Point(7) = {0, 0, -r, h_wall};
Circle(1) = {2, 1, 3}; Circle(2) = {3, 1, 5}; Circle(3) = {5, 1, 6}; Circle(4) = {6, 1, 2};
Circle(5) = {2, 1, 7}; Circle(6) = {7, 1, 5}; Circle(7) = {5, 1, 4}; Circle(8) = {4, 1, 2};
Circle(9) = {6, 1, 7}; Circle(10) = {7, 1, 3}; Circle(11) = {3, 1, 4}; Circle(12) = {4, 1, 6};
Curve Loop(1) = {1, 11, 8}; Surface(1) = {1};
Curve Loop(2) = {2, 7, -11}; Surface(2) = {2};
Curve Loop(3) = {3, -12, -7}; Surface(3) = {3};
Curve Loop(4) = {4, -8, 12}; Surface(4) = {4};
Curve Loop(5) = {5, 10, -1}; Surface(5) = {5};
Curve Loop(6) = {-2, -10, 6}; Surface(6) = {6};
Curve Loop(7) = {-3, -6, -9}; Surface(7) = {7};
Curve Loop(8) = {-4, 9, -5}; Surface(8) = {8};
Recombine Surface {1, 2};
For k In {0 : n_layers - 1}
  one[k] = 1;
  t[k] = h_first * (1.3^(k + 1) - 1) / 0.3;
EndFor
out[] = Extrude {Surface{1:8}; Layers{one[], t[]}; Recombine; };
Point(1001) = {-B, -B, -B, h_far}; Point(1002) = {B, -B, -B, h_far};
Point(1003) = {B, B, -B, h_far}; Point(1004) = {-B, B, -B, h_far};
Point(1005) = {-B, -B, B, h_far}; Point(1006) = {B, -B, B, h_far};
Point(1007) = {B, B, B, h_far}; Point(1008) = {-B, B, B, h_far};
Line(1001) = {1001, 1002}; Line(1002) = {1002, 1003}; Line(1003) = {1003, 1004}; Line(1004) = {1004, 1001};
Line(1005) = {1005, 1006}; Line(1006) = {1006, 1007}; Line(1007) = {1007, 1008}; Line(1008) = {1008, 1005};
Line(1009) = {1001, 1005}; Line(1010) = {1002, 1006}; Line(1011) = {1003, 1007}; Line(1012) = {1004, 1008};
Curve Loop(1001) = {-1001, -1004, -1003, -1002}; Plane Surface(2001) = {1001};
Curve Loop(1002) = {1005, 1006, 1007, 1008}; Plane Surface(2002) = {1002};
Curve Loop(1003) = {1001, 1010, -1005, -1009}; Plane Surface(2003) = {1003};
Curve Loop(1004) = {1002, 1011, -1006, -1010}; Plane Surface(2004) = {1004};
Curve Loop(1005) = {1003, 1012, -1007, -1011}; Plane Surface(2005) = {1005};
Curve Loop(1006) = {1004, 1009, -1008, -1012}; Plane Surface(2006) = {1006};
Surface Loop(1001) = {2001:2006};
Surface Loop(1002) = {out[0], out[5], out[10], out[15], out[20], out[25], out[30], out[35]};
Volume(100) = {1001, 1002};
Physical Surface("wall", 1) = {1:8};
Physical Surface("farfield", 2) = {2001:2006};
Physical Volume("domain", 3) = {out[1], out[6], out[11], out[16], out[21], out[26], out[31], out[36], 100};
