// patch_curved.geo -- the domain of the 2D hydrostatic patch test
// (tests/patch.rs): an annular sector with two curved sides, so that the
// quadratic elements along them are curved.
//
//          4 +.
//            |  ' .  3              radii 2 and 4, from 15 to 75 degrees
//            +.     +               about the origin
//              '.  body \           boundary: all four sides (pressure)
//                ' +-----+ 2        A = point 1, B = point 2 (supports)
//                  1
//
// quads = 0: unstructured triangles of size lc;
// quads = 1: transfinite quadrilaterals, n radially (graded), 2 n around.
// serendipity = 1 makes `gmsh -order 2` write quad8 instead of quad9.

DefineConstant[ quads = {0, Name "Parameters/quadrilaterals"} ];
DefineConstant[ serendipity = {0, Name "Parameters/serendipity"} ];
DefineConstant[ lc = {0.6, Name "Parameters/triangle size"} ];
DefineConstant[ n = {3, Name "Parameters/quads radially"} ];

r1 = 2.0;
r2 = 4.0;
t1 = 15 * Pi / 180;
t2 = 75 * Pi / 180;
Point(1) = {r1 * Cos(t1), r1 * Sin(t1), 0, lc};
Point(2) = {r2 * Cos(t1), r2 * Sin(t1), 0, lc};
Point(3) = {r2 * Cos(t2), r2 * Sin(t2), 0, lc};
Point(4) = {r1 * Cos(t2), r1 * Sin(t2), 0, lc};
Point(5) = {0, 0, 0, lc};

Line(1) = {1, 2};
Circle(2) = {2, 5, 3};
Line(3) = {3, 4};
Circle(4) = {4, 5, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};

If (quads)
  Transfinite Curve{1} = n + 1 Using Progression 1.3;
  Transfinite Curve{3} = n + 1;
  Transfinite Curve{2, 4} = 2 * n + 1;
  Transfinite Surface{1};
  Recombine Surface{1};
EndIf
Mesh.SecondOrderIncomplete = serendipity;

Physical Surface("body") = {1};
Physical Curve("boundary") = {1, 2, 3, 4};
Physical Point("A") = {1};
Physical Point("B") = {2};
