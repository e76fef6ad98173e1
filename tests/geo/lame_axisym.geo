// lame_axisym.geo -- Lame's thick-walled cylinder as an axisymmetric model
// for tests/lame.rs: the meridian section a <= x = r <= b, 0 <= y <= L
// (y is the axis), meshed with structured quadrilaterals.
//
//      y
//      |   top: y = L (axial displacement held)
//    L +---+---------+
//      |   |         |
//      |   | body    | outer: x = b (free)
//      |   |         |
//      +---+---------+--- x = r
//          a bottom  b      inner: x = a (pressure); bottom: y = 0 (held)
//
// (b - a)/lc quadrilaterals radially, L/lc axially.

DefineConstant[ lc = {0.25, Min 0.01, Max 1, Name "Parameters/element size"} ];
a = 3.0;
b = 5.0;
L = 1.0;

Point(1) = {a, 0, 0};
Point(2) = {b, 0, 0};
Point(3) = {b, L, 0};
Point(4) = {a, L, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};

Transfinite Curve{1, 3} = Ceil((b - a) / lc) + 1;
Transfinite Curve{2, 4} = Ceil(L / lc) + 1;
Transfinite Surface{1};
Recombine Surface{1};

Physical Surface("body") = {1};
Physical Curve("bottom") = {1};
Physical Curve("outer") = {2};
Physical Curve("top") = {3};
Physical Curve("inner") = {4};
