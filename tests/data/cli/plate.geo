// A 2D channel with an elliptic body: the CLI tests' independent Gmsh input.
// gmsh -2 -format msh22 plate.geo -o plate_v22.msh   (and msh41, mesh; see README.md)
lc_far = 0.5;
lc_body = 0.12;
Point(1) = {0, 0, 0, lc_far};
Point(2) = {4, 0, 0, lc_far};
Point(3) = {4, 2, 0, lc_far};
Point(4) = {0, 2, 0, lc_far};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
// ellipse centred at (1.5, 1), semi-axes 0.5 and 0.15
Point(5) = {1.5, 1, 0, lc_body};
Point(6) = {2.0, 1, 0, lc_body};
Point(7) = {1.5, 1.15, 0, lc_body};
Point(8) = {1.0, 1, 0, lc_body};
Point(9) = {1.5, 0.85, 0, lc_body};
Ellipse(5) = {6, 5, 6, 7};
Ellipse(6) = {7, 5, 6, 8};
Ellipse(7) = {8, 5, 6, 9};
Ellipse(8) = {9, 5, 6, 6};
Curve Loop(1) = {1, 2, 3, 4};
Curve Loop(2) = {5, 6, 7, 8};
Plane Surface(1) = {1, 2};
Physical Curve("farfield", 1) = {1, 2, 3, 4};
Physical Curve("wing", 2) = {5, 6, 7, 8};
Physical Surface("fluid", 10) = {1};
