// The cube [-2,2]^3 with the cubic hole [-0.5,0.5]^3: the domain of
// examples/deform_c3t3.cpp. Mesh it with Debian's gmsh (4.8.4), from this
// directory:
//   gmsh -3 -format mesh cube_hole_3d.geo -o cube_hole_3d.mesh
// Physical groups: surfaces "outer" (1) and "hole" (2), volume "fluid" (10);
// they become the Medit triangle and tetrahedron references.
SetFactory("OpenCASCADE");
h_outer = 0.8;  // mesh size on the outer cube
h_hole = 0.25;  // mesh size on the hole: finer where the mesh moves most
Box(1) = {-2, -2, -2, 4, 4, 4};
Box(2) = {-0.5, -0.5, -0.5, 1, 1, 1};
BooleanDifference(3) = { Volume{1}; Delete; }{ Volume{2}; Delete; };
MeshSize{ PointsOf{ Volume{3}; } } = h_outer;
MeshSize{ PointsOf{ Surface{7:12}; } } = h_hole;
Physical Surface("outer", 1) = {1:6};
Physical Surface("hole", 2) = {7:12};
Physical Volume("fluid", 10) = {3};
// Medit references are the physical tags (Gmsh writes the elementary ones by default)
Mesh.SaveElementTagType = 2;
