// The square [-2,2]^2 with the square hole [-0.5,0.5]^2: the domain of the
// examples rotate_square_hole_2d and custom_stiffness_2d, as a file for the
// command-line tool. Mesh it with Debian's gmsh (4.8.4), from this directory:
//   gmsh -2 -format mesh square_hole_2d.geo -o square_hole_2d.mesh
// Physical groups: curves "outer" (1) and "hole" (2), surface "fluid" (10);
// they become the Medit edge and triangle references (see the last line).
h_outer = 0.4;  // mesh size on the outer square
h_hole = 0.125; // mesh size on the hole: finer where the mesh moves most
Point(1) = {-2, -2, 0, h_outer};
Point(2) = {2, -2, 0, h_outer};
Point(3) = {2, 2, 0, h_outer};
Point(4) = {-2, 2, 0, h_outer};
Point(5) = {-0.5, -0.5, 0, h_hole};
Point(6) = {0.5, -0.5, 0, h_hole};
Point(7) = {0.5, 0.5, 0, h_hole};
Point(8) = {-0.5, 0.5, 0, h_hole};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Line(5) = {5, 6};
Line(6) = {6, 7};
Line(7) = {7, 8};
Line(8) = {8, 5};
Curve Loop(1) = {1, 2, 3, 4};
Curve Loop(2) = {5, 6, 7, 8};
Plane Surface(1) = {1, 2};
Physical Curve("outer", 1) = {1, 2, 3, 4};
Physical Curve("hole", 2) = {5, 6, 7, 8};
Physical Surface("fluid", 10) = {1};
// Medit references are the physical tags (Gmsh writes the elementary ones by default)
Mesh.SaveElementTagType = 2;
