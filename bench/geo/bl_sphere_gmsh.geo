// SPDX-License-Identifier: MIT
// Paper 000 §5.3 in 3D for Gmsh's high-order optimizer (scripts/bench-gmsh-ho --3d): the unit
// sphere (centre 0) with a boundary layer extruded along its normals (first layer h_first,
// growth 1.3, as many layers as reach the wall size h_wall; gmsh splits the prisms into
// tetrahedra), inside the sphere of radius 5 (size h_far). Built-in kernel: the boundary-layer
// extrusion needs it. Groups: "wall" (1), "farfield" (2), "domain" (3).
If (!Exists(h_first)) h_first = 1e-2; EndIf
If (!Exists(h_wall)) h_wall = 0.8; EndIf
If (!Exists(h_far)) h_far = 3; EndIf
R = 5;
Point(1) = {0, 0, 0, h_wall};
Point(2) = {1, 0, 0, h_wall}; Point(3) = {0, 1, 0, h_wall}; Point(4) = {0, 0, 1, h_wall};
Point(5) = {-1, 0, 0, h_wall}; Point(6) = {0, -1, 0, h_wall}; Point(7) = {0, 0, -1, h_wall};
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
n = Ceil(Log(h_wall / h_first) / Log(1.3)) + 1;
For k In {0 : n - 1}
  one[k] = 1;
  t[k] = h_first * (1.3^(k + 1) - 1) / 0.3;
EndFor
out[] = Extrude {Surface{1:8}; Layers{one[], t[]}; };
Point(1002) = {R, 0, 0, h_far}; Point(1003) = {0, R, 0, h_far}; Point(1004) = {0, 0, R, h_far};
Point(1005) = {-R, 0, 0, h_far}; Point(1006) = {0, -R, 0, h_far}; Point(1007) = {0, 0, -R, h_far};
Circle(1001) = {1002, 1, 1003}; Circle(1002) = {1003, 1, 1005}; Circle(1003) = {1005, 1, 1006}; Circle(1004) = {1006, 1, 1002};
Circle(1005) = {1002, 1, 1007}; Circle(1006) = {1007, 1, 1005}; Circle(1007) = {1005, 1, 1004}; Circle(1008) = {1004, 1, 1002};
Circle(1009) = {1006, 1, 1007}; Circle(1010) = {1007, 1, 1003}; Circle(1011) = {1003, 1, 1004}; Circle(1012) = {1004, 1, 1006};
Curve Loop(1001) = {1001, 1011, 1008}; Surface(2001) = {1001};
Curve Loop(1002) = {1002, 1007, -1011}; Surface(2002) = {1002};
Curve Loop(1003) = {1003, -1012, -1007}; Surface(2003) = {1003};
Curve Loop(1004) = {1004, -1008, 1012}; Surface(2004) = {1004};
Curve Loop(1005) = {1005, 1010, -1001}; Surface(2005) = {1005};
Curve Loop(1006) = {-1002, -1010, 1006}; Surface(2006) = {1006};
Curve Loop(1007) = {-1003, -1006, -1009}; Surface(2007) = {1007};
Curve Loop(1008) = {-1004, 1009, -1005}; Surface(2008) = {1008};
Surface Loop(1001) = {2001:2008};
Surface Loop(1002) = {out[0], out[5], out[10], out[15], out[20], out[25], out[30], out[35]};
Volume(100) = {1001, 1002};
Physical Surface("wall", 1) = {1:8};
Physical Surface("farfield", 2) = {2001:2008};
Physical Volume("domain", 3) = {out[1], out[6], out[11], out[16], out[21], out[26], out[31], out[36], 100};
