// A channel with a cylinder, one layer thick (prisms), for gmshToFoam.
h = 0.12;
Point(1) = {0, 0, 0, h}; Point(2) = {1.2, 0, 0, h}; Point(3) = {1.2, 0.41, 0, h}; Point(4) = {0, 0.41, 0, h};
Point(5) = {0.3, 0.2, 0, h}; Point(6) = {0.35, 0.2, 0, h / 3}; Point(7) = {0.3, 0.25, 0, h / 3};
Point(8) = {0.25, 0.2, 0, h / 3}; Point(9) = {0.3, 0.15, 0, h / 3};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Circle(5) = {6, 5, 7}; Circle(6) = {7, 5, 8}; Circle(7) = {8, 5, 9}; Circle(8) = {9, 5, 6};
Curve Loop(1) = {1, 2, 3, 4}; Curve Loop(2) = {5, 6, 7, 8};
Plane Surface(1) = {1, 2};
out[] = Extrude {0, 0, 0.05} { Surface{1}; Layers{1}; Recombine; };
Physical Surface("back") = {1};
Physical Surface("front") = {out[0]};
Physical Surface("walls") = {out[2], out[4]};
Physical Surface("inlet") = {out[5]};
Physical Surface("outlet") = {out[3]};
Physical Surface("cylinder") = {out[6], out[7], out[8], out[9]};
Physical Volume("fluid") = {out[1]};
Mesh.MshFileVersion = 2.2;
