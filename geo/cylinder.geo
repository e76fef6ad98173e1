// cylinder.geo -- the seed paper's example: a thick-walled cylinder under
// internal pressure, quarter model, cut along the 45-degree radial line A-A
// into two bodies that meet in contact.
//
// Sample runs:
//   subcontact solve geo/cylinder.toml                 (lc = 0.1, quad9)
//   gmsh geo/cylinder.geo -2 -setnumber lc 0.05        (mesh only)
//
//        y
//        |
//      7 +.
//        |   .  body_2
//      6 +.     .   5
//        |  .     /        A-A: the cut at 45 degrees (contact)
//        |    . /   .      inner: r = a (pressure), outer: r = b (free)
//        |     4      .    symmetry_x0: x = 0, symmetry_y0: y = 0
//        |      .body_1.
//        +-------+------+--- x
//        1       2      3
//
// Structured quadrilaterals: (b - a)/lc elements radially, about
// (pi/4) r_mean / lc around each body, so the nodes on A-A lie every lc.

DefineConstant[ lc = {0.1, Min 0.002, Max 1, Name "Parameters/element size"} ];
a = 3.0;
b = 5.0;

Point(1) = {0, 0, 0};
Point(2) = {a, 0, 0};
Point(3) = {b, 0, 0};
Point(4) = {a * Cos(Pi/4), a * Sin(Pi/4), 0};
Point(5) = {b * Cos(Pi/4), b * Sin(Pi/4), 0};
Point(6) = {0, a, 0};
Point(7) = {0, b, 0};

Line(1) = {2, 3};          // y = 0
Circle(2) = {3, 1, 5};     // outer arc of body_1
Line(3) = {5, 4};          // the cut A-A
Circle(4) = {4, 1, 2};     // inner arc of body_1
Circle(5) = {5, 1, 7};     // outer arc of body_2
Line(6) = {7, 6};          // x = 0
Circle(7) = {6, 1, 4};     // inner arc of body_2

Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Curve Loop(2) = {-3, 5, 6, 7};
Plane Surface(2) = {2};

nr = Ceil((b - a) / lc) + 1;
nt = Ceil(Pi / 4 * (a + b) / 2 / lc) + 1;
Transfinite Curve{1, 3, 6} = nr;
Transfinite Curve{2, 4, 5, 7} = nt;
Transfinite Surface{1, 2};
Recombine Surface{1, 2};

Physical Surface("body_1") = {1};
Physical Surface("body_2") = {2};
Physical Curve("A-A") = {3};
Physical Curve("inner") = {4, 7};
Physical Curve("outer") = {2, 5};
Physical Curve("symmetry_y0") = {1};
Physical Curve("symmetry_x0") = {6};
