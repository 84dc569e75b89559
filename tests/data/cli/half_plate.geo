// The lower half of plate.geo's channel, cut along its symmetry line y = 1
// (moved to y = 0): the half ellipse sits on the line `symmetry`, which the
// CLI tests let slide. Physical curves `farfield` (1), `wing` (2),
// `symmetry` (3), surface `fluid` (10).
lc_far = 0.4;
lc_body = 0.1;
Point(1) = {0, 0, 0, lc_far};
Point(2) = {1.0, 0, 0, lc_body};
Point(3) = {2.0, 0, 0, lc_body};
Point(4) = {4, 0, 0, lc_far};
Point(5) = {4, 1, 0, lc_far};
Point(6) = {0, 1, 0, lc_far};
Point(7) = {1.5, 0, 0, lc_body};
Point(8) = {1.5, 0.15, 0, lc_body};
Line(1) = {1, 2};
Ellipse(2) = {2, 7, 3, 8};
Ellipse(3) = {8, 7, 3, 3};
Line(4) = {3, 4};
Line(5) = {4, 5};
Line(6) = {5, 6};
Line(7) = {6, 1};
Curve Loop(1) = {1, 2, 3, 4, 5, 6, 7};
Plane Surface(1) = {1};
Physical Curve("farfield", 1) = {5, 6, 7};
Physical Curve("wing", 2) = {2, 3};
Physical Curve("symmetry", 3) = {1, 4};
Physical Surface("fluid", 10) = {1};
