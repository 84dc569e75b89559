// A 3D box with a cubic body inside: the CLI tests' 3D Gmsh input.
// gmsh -3 -format msh41 box_hole.geo -o box_hole_v41.msh   (and .mesh; see README.md)
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 2, 2, 2};
Box(2) = {0.7, 0.7, 0.7, 0.6, 0.6, 0.6};
BooleanDifference(3) = { Volume{1}; Delete; }{ Volume{2}; Delete; };
Mesh.MeshSizeMax = 0.5;
Mesh.MeshSizeMin = 0.2;
body() = Surface In BoundingBox{0.6, 0.6, 0.6, 1.4, 1.4, 1.4};
outer() = Surface In BoundingBox{-0.1, -0.1, -0.1, 2.1, 2.1, 2.1};
outer() -= body();
Physical Surface("body", 1) = {body()};
Physical Surface("outer", 2) = {outer()};
Physical Volume("fluid", 10) = {3};
