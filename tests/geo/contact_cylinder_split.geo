// contact_cylinder_split.geo -- geo/cylinder.geo with the cut A-A meshed
// twice: each body has its own copy of the cut (its own points and its own
// transfinite line, equal divisions), so the two sides have distinct but
// coincident nodes and the scene pairs them with groups = ["a", "b"].
//
//        y
//      7 +.
//        |   .  body_2
//      6 +.     .   9 5     cut_2 = 9-8 (body_2's side, group "b")
//        |  .     //        cut_1 = 5-4 (body_1's side, group "a")
//        |    . //   .
//        |     8 4     .
//        |      .body_1.
//        +-------+------+--- x
//        1       2      3
//
// Same parameters and node positions as geo/cylinder.geo (with extra = 0).

DefineConstant[ lc = {0.1, Min 0.002, Max 1, Name "Parameters/element size"} ];
// extra > 0 puts more divisions on body_2's side: unpaired nodes (a bad mesh)
DefineConstant[ extra = {0, Name "Parameters/extra divisions on cut_2"} ];
a = 3.0;
b = 5.0;
Geometry.AutoCoherence = 0;   // keep the coincident points apart

Point(1) = {0, 0, 0};
Point(2) = {a, 0, 0};
Point(3) = {b, 0, 0};
Point(4) = {a * Cos(Pi/4), a * Sin(Pi/4), 0};
Point(5) = {b * Cos(Pi/4), b * Sin(Pi/4), 0};
Point(6) = {0, a, 0};
Point(7) = {0, b, 0};
Point(8) = {a * Cos(Pi/4), a * Sin(Pi/4), 0};
Point(9) = {b * Cos(Pi/4), b * Sin(Pi/4), 0};

Line(1) = {2, 3};          // y = 0
Circle(2) = {3, 1, 5};     // outer arc of body_1
Line(3) = {5, 4};          // cut, body_1's side
Circle(4) = {4, 1, 2};     // inner arc of body_1
Circle(5) = {9, 1, 7};     // outer arc of body_2
Line(6) = {7, 6};          // x = 0
Circle(7) = {6, 1, 8};     // inner arc of body_2
Line(8) = {9, 8};          // cut, body_2's side

Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Curve Loop(2) = {-8, 5, 6, 7};
Plane Surface(2) = {2};

nr = Ceil((b - a) / lc) + 1;
nt = Ceil(Pi / 4 * (a + b) / 2 / lc) + 1;
Transfinite Curve{1, 3} = nr;
Transfinite Curve{6, 8} = nr + extra;
Transfinite Curve{2, 4, 5, 7} = nt;
Transfinite Surface{1, 2};
Recombine Surface{1, 2};

Physical Surface("body_1") = {1};
Physical Surface("body_2") = {2};
Physical Curve("a") = {3};
Physical Curve("b") = {8};
Physical Curve("inner") = {4, 7};
Physical Curve("outer") = {2, 5};
Physical Curve("symmetry_y0") = {1};
Physical Curve("symmetry_x0") = {6};
