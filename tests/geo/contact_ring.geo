// contact_ring.geo -- a quarter of a thick-walled cylinder (a = 3, b = 5)
// made of two rings that meet in contact along the circle r = c = 4: a
// curved interface whose end nodes lie on the symmetry lines, where they
// are supported (x = 0: ux held; y = 0: uy held).
//
//        y
//      9 +.
//        |   .   outer ring (r = 4..5)
//      8 +.     .
//        |  .     .         "joint": the arc r = 4 (shared curve)
//      7 +.   .     .       "inner": r = 3 (pressure)
//        |  .  .     .
//        +---+---+---+--- x "symmetry_y0" (y = 0), "symmetry_x0" (x = 0)
//        1   2   3   4
//
// quad = 1: transfinite quadrilaterals; quad = 0: unstructured triangles.

DefineConstant[ lc = {0.25, Name "Parameters/element size"} ];
DefineConstant[ quad = {1, Name "Parameters/quadrilaterals"} ];
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

nr = Ceil((c - a) / lc) + 1;
nt = Ceil(Pi / 2 * c / lc) + 1;
Transfinite Curve{1, 2, 6, 7} = nr;
Transfinite Curve{3, 4, 5} = nt;
If (quad)
  Transfinite Surface{1, 2};
  Recombine Surface{1, 2};
EndIf

Physical Surface("inner_ring") = {1};
Physical Surface("outer_ring") = {2};
Physical Curve("joint") = {4};
Physical Curve("inner") = {3};
Physical Curve("symmetry_y0") = {1, 2};
Physical Curve("symmetry_x0") = {6, 7};
