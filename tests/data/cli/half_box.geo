// The lower half of box_hole.geo's box, cut along its symmetry plane z = 1
// (moved to z = 0): the half cube sits on the plane `symmetry`, which the
// CLI tests let slide. Physical surfaces `body` (1), `outer` (2),
// `symmetry` (3), volume `fluid` (10).
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 2, 2, 1};
Box(2) = {0.7, 0.7, 0, 0.6, 0.6, 0.3};
BooleanDifference(3) = { Volume{1}; Delete; }{ Volume{2}; Delete; };
Mesh.MeshSizeMax = 0.4;
Mesh.MeshSizeMin = 0.15;
eps = 1e-6;
symmetry() = Surface In BoundingBox{-eps, -eps, -eps, 2 + eps, 2 + eps, eps};
body() = Surface In BoundingBox{0.7 - eps, 0.7 - eps, -eps, 1.3 + eps, 1.3 + eps, 0.3 + eps};
body() -= symmetry();
outer() = Surface In BoundingBox{-eps, -eps, -eps, 2 + eps, 2 + eps, 1 + eps};
outer() -= body();
outer() -= symmetry();
Physical Surface("body", 1) = {body()};
Physical Surface("outer", 2) = {outer()};
Physical Surface("symmetry", 3) = {symmetry()};
Physical Volume("fluid", 10) = {3};
