// NACA0012 airfoil (chord 1, closed trailing edge) in a circular far field of
// radius 10 centred at (0.5, 0): the input of the README's "Your own mesh"
// walk-through. Mesh it with Debian's gmsh:
//   gmsh -2 -format msh41 data/naca0012_2d.geo -o naca0012_2d.msh
// Physical groups: curves "airfoil" (1) and "farfield" (2), surface "fluid" (10).
N = 50;            // points per surface, cosine spaced
lc_airfoil = 0.02; // mesh size at the airfoil
lc_far = 1.5;      // mesh size at the far field
R = 10;

// y_t(x) of docs/method.md ("Test cases"), with -0.1036 for a closed trailing edge
Point(1) = {1, 0, 0, lc_airfoil};             // trailing edge
For i In {1:N-1}
  x = 0.5 * (1 + Cos(Pi * i / N));            // from the trailing edge to the leading edge
  y = 0.6 * (0.2969 * Sqrt(x) - 0.1260 * x - 0.3516 * x^2 + 0.2843 * x^3 - 0.1036 * x^4);
  Point(1 + i) = {x, y, 0, lc_airfoil};       // upper surface
  Point(1 + N + i) = {x, -y, 0, lc_airfoil};  // lower surface
EndFor
Point(1 + N) = {0, 0, 0, lc_airfoil};         // leading edge
upper[] = {1};
For i In {1:N-1}
  upper[] += {1 + i};
EndFor
upper[] += {1 + N};
lower[] = {1 + N};
For i In {N-1:1:-1}
  lower[] += {1 + N + i};
EndFor
lower[] += {1};
Spline(1) = upper[];                          // trailing edge -> leading edge, over the top
Spline(2) = lower[];                          // leading edge -> trailing edge, underneath
Curve Loop(1) = {1, 2};

Point(1000) = {0.5, 0, 0, lc_far};
Point(1001) = {0.5 + R, 0, 0, lc_far};
Point(1002) = {0.5, R, 0, lc_far};
Point(1003) = {0.5 - R, 0, 0, lc_far};
Point(1004) = {0.5, -R, 0, lc_far};
Circle(11) = {1001, 1000, 1002};
Circle(12) = {1002, 1000, 1003};
Circle(13) = {1003, 1000, 1004};
Circle(14) = {1004, 1000, 1001};
Curve Loop(2) = {11, 12, 13, 14};

Plane Surface(1) = {2, 1};
Mesh.MeshSizeExtendFromBoundary = 1;
Physical Curve("airfoil", 1) = {1, 2};
Physical Curve("farfield", 2) = {11, 12, 13, 14};
Physical Surface("fluid", 10) = {1};
