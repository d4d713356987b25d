// Prisms and hexahedra in 2 layers on a base bounded by a circular arc, tetrahedra above them,
// pyramids where the tetrahedra meet the hexahedra's top faces; quadratic, incomplete:
// gmsh -3 -order 2 -setnumber Mesh.SecondOrderIncomplete 1 (see serendipity_meshes.py).
SetFactory("Built-in");
Point(1) = {0,0,0,1.2}; Point(2) = {1,0,0,1.2}; Point(3) = {1,1,0,1.2}; Point(4) = {0,1,0,1.2};
Point(5) = {2,0,0,1.2}; Point(6) = {2,1,0,1.2}; Point(7) = {0.5,0.5,0,1.2};
Line(1) = {1,2}; Line(2) = {2,3}; Line(3) = {3,4}; Circle(4) = {4,7,1};
Line(5) = {2,5}; Line(6) = {5,6}; Line(7) = {6,3};
Curve Loop(1) = {1,2,3,4}; Plane Surface(1) = {1};
Curve Loop(2) = {5,6,7,-2}; Plane Surface(2) = {2};
Transfinite Curve{5,6,7,2} = 2; Transfinite Surface{2}; Recombine Surface{2};
a[] = Extrude {0,0,0.2} { Surface{1}; Layers{2}; Recombine; };
b[] = Extrude {0,0,0.2} { Surface{2}; Layers{2}; Recombine; };
c[] = Extrude {0,0,0.6} { Surface{a[0]}; };
d[] = Extrude {0,0,0.6} { Surface{b[0]}; };
Physical Surface("bottom") = {1, 2};
Physical Surface("arc") = {a[5]};
Physical Volume("domain") = {a[1], b[1], c[1], d[1]};
