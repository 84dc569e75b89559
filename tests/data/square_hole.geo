// Unit square with a circular hole: a small 2D domain with two labelled
// boundaries, for the Gmsh reader tests (see README.md).
h = 0.25;
Point(1) = {0, 0, 0, h};
Point(2) = {1, 0, 0, h};
Point(3) = {1, 1, 0, h};
Point(4) = {0, 1, 0, h};
Point(5) = {0.5, 0.5, 0, h};
Point(6) = {0.7, 0.5, 0, h};
Point(7) = {0.5, 0.7, 0, h};
Point(8) = {0.3, 0.5, 0, h};
Point(9) = {0.5, 0.3, 0, h};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Circle(5) = {6, 5, 7};
Circle(6) = {7, 5, 8};
Circle(7) = {8, 5, 9};
Circle(8) = {9, 5, 6};
Curve Loop(1) = {1, 2, 3, 4};
Curve Loop(2) = {5, 6, 7, 8};
Plane Surface(1) = {1, 2};
Physical Curve("outer", 1) = {1, 2, 3, 4};
Physical Curve("hole", 2) = {5, 6, 7, 8};
Physical Surface("fluid", 10) = {1};
