// Gmsh 4.8.4: gmsh -3 hybrid_layer.geo -format msh41 -o hybrid_layer.msh. Prisms (a triangle mesh
// extruded in 3 layers) and hexahedra (a quadrilateral one) under tetrahedra, with pyramids
// where the tetrahedra meet the hexahedra's top faces.
SetFactory("Built-in");
Point(1) = {0,0,0,0.5}; Point(2) = {1,0,0,0.5}; Point(3) = {1,1,0,0.5}; Point(4) = {0,1,0,0.5};
Point(5) = {2,0,0,0.5}; Point(6) = {2,1,0,0.5};
Line(1) = {1,2}; Line(2) = {2,3}; Line(3) = {3,4}; Line(4) = {4,1}; Line(5) = {2,5}; Line(6) = {5,6}; Line(7) = {6,3};
Curve Loop(1) = {1,2,3,4}; Plane Surface(1) = {1};
Curve Loop(2) = {5,6,7,-2}; Plane Surface(2) = {2};
Transfinite Curve{5,6,7,2} = 3; Transfinite Surface{2}; Recombine Surface{2};
a[] = Extrude {0,0,0.1} { Surface{1}; Layers{{3},{1}}; Recombine; };
b[] = Extrude {0,0,0.1} { Surface{2}; Layers{{3},{1}}; Recombine; };
c[] = Extrude {0,0,0.9} { Surface{a[0]}; };
d[] = Extrude {0,0,0.9} { Surface{b[0]}; };
Physical Surface("bottom") = {1, 2};
Physical Volume("domain") = {a[1], b[1], c[1], d[1]};

