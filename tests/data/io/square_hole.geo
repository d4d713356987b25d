SetFactory("OpenCASCADE");
Rectangle(1) = {0, 0, 0, 2, 1};
Disk(2) = {0.6, 0.5, 0, 0.2};
BooleanDifference{ Surface{1}; Delete; }{ Surface{2}; Delete; }
Mesh.MeshSizeMax = 0.35;
Physical Surface("fluid", 10) = {1};
Physical Curve("hole wall", 20) = {5};
Physical Curve("outer", 21) = {6, 7, 8, 9};
