// patch_axis.geo -- the domain of the axisymmetric patch test on the axis
// (tests/patch.rs): a quadrilateral with one side on the axis x = r = 0
// and no two sides parallel.
//
//      y (axis)
//      |
//    4 +----------+ 3          side_12, side_23, side_34: physical curves
//      |           \           (tractions); axis: the side on r = 0
//      | axis body  \          A = point 1 (support)
//      |        ..---+ 2
//    1 +---'''
//
// quads = 0: unstructured triangles of size lc;
// quads = 1: a transfinite n x n grid of quadrilaterals.
// serendipity = 1 makes `gmsh -order 2` write quad8 instead of quad9.
//
// tests/patch.rs reads the Point coordinates: keep them literal numbers.

DefineConstant[ quads = {0, Name "Parameters/quadrilaterals"} ];
DefineConstant[ serendipity = {0, Name "Parameters/serendipity"} ];
DefineConstant[ lc = {0.6, Name "Parameters/triangle size"} ];
DefineConstant[ n = {4, Name "Parameters/quadrilaterals per side"} ];

Point(1) = {0.0, 0.0, 0, lc};
Point(2) = {3.0, 0.4, 0, lc};
Point(3) = {2.6, 2.8, 0, lc};
Point(4) = {0.0, 2.2, 0, lc};

Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};

If (quads)
  Transfinite Curve{1:4} = n + 1;
  Transfinite Surface{1};
  Recombine Surface{1};
EndIf
Mesh.SecondOrderIncomplete = serendipity;

Physical Surface("body") = {1};
Physical Curve("side_12") = {1};
Physical Curve("side_23") = {2};
Physical Curve("side_34") = {3};
Physical Curve("axis") = {4};
Physical Point("A") = {1};
