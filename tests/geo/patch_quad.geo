// patch_quad.geo -- the domain of the 2D patch tests (tests/patch.rs), after
// MacNeal and Harder's distorted patch: a general quadrilateral (no two
// sides parallel) cut into five quadrilateral blocks by an irregular inner
// quadrilateral 5678. It lies in x >= 1 so that it also serves axisymmetric
// models (r = x, axis = y).
//
//                            3
//          4 +'''''''''''''''+
//           / \ 8 +------+ 7 |
//          /   \ /        \  |      side_12, side_23, side_34, side_41:
//         /   5 +----------+ 6      one physical curve per side (tractions)
//        /  ..''          '' \      A = point 1, B = point 2 (supports)
//     1 +''-------------------+ 2
//
// quads = 0: unstructured triangles of size lc (irregular by nature);
// quads = 1: every block a transfinite n x n grid of quadrilaterals (n = 1 is
//            MacNeal and Harder's five-element patch), none a parallelogram.
// serendipity = 1 makes `gmsh -order 2` write quad8 instead of quad9.
//
// tests/patch.rs reads the Point coordinates to compute the outward normal
// of each side: keep them literal numbers.

DefineConstant[ quads = {0, Name "Parameters/quadrilaterals"} ];
DefineConstant[ serendipity = {0, Name "Parameters/serendipity"} ];
DefineConstant[ lc = {0.6, Name "Parameters/triangle size"} ];
DefineConstant[ n = {2, Name "Parameters/quadrilaterals per block side"} ];

Point(1) = {1.0, 0.0, 0, lc};
Point(2) = {4.6, 0.7, 0, lc};
Point(3) = {4.0, 3.4, 0, lc};
Point(4) = {1.4, 2.6, 0, lc};
Point(5) = {1.8, 0.7, 0, lc};
Point(6) = {3.7, 1.0, 0, lc};
Point(7) = {3.4, 2.5, 0, lc};
Point(8) = {2.0, 1.9, 0, lc};

// the sides 1-4, the inner quadrilateral 5-8, corner i to inner corner i + 4: 9-12
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Line(5) = {5, 6};
Line(6) = {6, 7};
Line(7) = {7, 8};
Line(8) = {8, 5};
Line(9) = {1, 5};
Line(10) = {2, 6};
Line(11) = {3, 7};
Line(12) = {4, 8};

Curve Loop(1) = {5, 6, 7, 8};
Plane Surface(1) = {1};
Curve Loop(2) = {1, 10, -5, -9};
Plane Surface(2) = {2};
Curve Loop(3) = {2, 11, -6, -10};
Plane Surface(3) = {3};
Curve Loop(4) = {3, 12, -7, -11};
Plane Surface(4) = {4};
Curve Loop(5) = {4, 9, -8, -12};
Plane Surface(5) = {5};

If (quads)
  Transfinite Curve{1:12} = n + 1;
  Transfinite Surface{1:5};
  Recombine Surface{1:5};
EndIf
Mesh.SecondOrderIncomplete = serendipity;

Physical Surface("body") = {1:5};
Physical Curve("side_12") = {1};
Physical Curve("side_23") = {2};
Physical Curve("side_34") = {3};
Physical Curve("side_41") = {4};
Physical Point("A") = {1};
Physical Point("B") = {2};
