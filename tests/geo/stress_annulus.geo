// stress_annulus.geo -- a quarter of a thick-walled cylinder (a = 3, b = 5)
// made of two rings that meet along the circle r = c = 4: the compound
// cylinder of tests/stress.rs (rings of different stiffness, bonded by a
// contact that stays stuck) and, with no contact in the scene (the rings
// share the joint's nodes), Lame's cylinder for the locking study.
//
//        y
//      9 +.
//        |   .   outer_ring (r = c..b)
//      8 +.     .
//        |  .     .         "joint": the arc r = c (shared curve)
//      7 +.   .     .       "inner": r = a (pressure), "outer": r = b
//        |  .  .     .
//        +---+---+---+--- x "symmetry_y0" (y = 0), "symmetry_x0" (x = 0)
//        1   2   3   4
//
// quad = 1: transfinite quadrilaterals; quad = 0: unstructured triangles
// (same divisions on every curve). serendipity = 1: quad8 for order 2.

DefineConstant[ lc = {0.25, Name "Parameters/element size"} ];
DefineConstant[ quad = {1, Name "Parameters/quadrilaterals"} ];
DefineConstant[ serendipity = {0, Name "Parameters/quad8 instead of quad9"} ];
Mesh.SecondOrderIncomplete = serendipity;
a = 3.0;
c = 4.0;
b = 5.0;

Point(1) = {0, 0, 0};
Point(2) = {a, 0, 0};
Point(3) = {c, 0, 0};
Point(4) = {b, 0, 0};
Point(7) = {0, a, 0};
Point(8) = {0, c, 0};
Point(9) = {0, b, 0};

Line(1) = {2, 3};
Line(2) = {3, 4};
Circle(3) = {2, 1, 7};     // inner
Circle(4) = {3, 1, 8};     // joint
Circle(5) = {4, 1, 9};     // outer
Line(6) = {8, 7};
Line(7) = {9, 8};

Curve Loop(1) = {1, 4, 6, -3};
Plane Surface(1) = {1};
Curve Loop(2) = {2, 5, 7, -4};
Plane Surface(2) = {2};

nr1 = Ceil((c - a) / lc) + 1;
nr2 = Ceil((b - c) / lc) + 1;
nt = Ceil(Pi / 2 * c / lc) + 1;
Transfinite Curve{1, 6} = nr1;
Transfinite Curve{2, 7} = nr2;
Transfinite Curve{3, 4, 5} = nt;
If (quad)
  Transfinite Surface{1, 2};
  Recombine Surface{1, 2};
EndIf

Physical Surface("inner_ring") = {1};
Physical Surface("outer_ring") = {2};
Physical Curve("joint") = {4};
Physical Curve("inner") = {3};
Physical Curve("outer") = {5};
Physical Curve("symmetry_y0") = {1, 2};
Physical Curve("symmetry_x0") = {6, 7};
