// Unit cube with labelled faces: a small 3D domain for the Gmsh 4.1 reader
// tests (see README.md).
SetFactory("Built-in");
h = 0.5;
Point(1) = {0, 0, 0, h};
Point(2) = {1, 0, 0, h};
Point(3) = {1, 1, 0, h};
Point(4) = {0, 1, 0, h};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
out[] = Extrude {0, 0, 1} { Surface{1}; };
// out[0]: top, out[1]: volume, out[2..5]: sides along lines 1..4
Physical Surface("inlet", 1) = {out[5]};   // x = 0 (from line 4)
Physical Surface("outlet", 2) = {out[3]};  // x = 1 (from line 2)
Physical Surface("walls", 3) = {1, out[0], out[2], out[4]};
Physical Volume("domain", 100) = {out[1]};
