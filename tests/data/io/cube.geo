SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Mesh.MeshSizeMin = 0.5; Mesh.MeshSizeMax = 0.5; Mesh.MeshSizeFromPoints = 0;
Physical Volume("solid", 1) = {1};
Physical Surface("bottom", 2) = {5};
Physical Surface("sides", 3) = {1, 2, 3, 4, 6};
