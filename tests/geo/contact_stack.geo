// contact_stack.geo -- two blocks stacked along y, in contact along the
// horizontal line y = h; the contact patch test of tests/contact.rs.
//
//   y
//   |  top (traction on "top_face")
// 2h +-----------+
//    |   top     |
//  h +-----------+   contact "joint" (shared curve, one node set)
//    |  bottom   |
//  0 +-----------+-- x      "base": y = 0; "corner": the point (x0, 0)
//    x0          x0 + w
//
// quad = 1: transfinite quadrilaterals (n x n per block); quad = 0:
// unstructured triangles with the same n divisions on every edge, so the
// joint is not a mesh line of symmetry.

DefineConstant[ n = {4, Name "Parameters/divisions per edge"} ];
DefineConstant[ quad = {1, Name "Parameters/quadrilaterals"} ];
DefineConstant[ serendipity = {0, Name "Parameters/quad8 instead of quad9"} ];
DefineConstant[ x0 = {0, Name "Parameters/x of the left side"} ];
Mesh.SecondOrderIncomplete = serendipity;
w = 2.0;
h = 1.0;

Point(1) = {x0, 0, 0};
Point(2) = {x0 + w, 0, 0};
Point(3) = {x0 + w, h, 0};
Point(4) = {x0, h, 0};
Point(5) = {x0 + w, 2 * h, 0};
Point(6) = {x0, 2 * h, 0};

Line(1) = {1, 2};   // base
Line(2) = {2, 3};
Line(3) = {3, 4};   // the joint
Line(4) = {4, 1};
Line(5) = {3, 5};
Line(6) = {5, 6};   // top face
Line(7) = {6, 4};

Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Curve Loop(2) = {-3, 5, 6, 7};
Plane Surface(2) = {2};

Transfinite Curve{1, 3, 6} = n + 1;
// uneven divisions up the sides: the mesh is no lattice of the solution
Transfinite Curve{2, 4, 5, 7} = n + 1 Using Progression 1.3;
If (quad)
  Transfinite Surface{1, 2};
  Recombine Surface{1, 2};
EndIf

Physical Surface("bottom") = {1};
Physical Surface("top") = {2};
Physical Curve("joint") = {3};
Physical Curve("base") = {1};
Physical Curve("top_face") = {6};
Physical Point("corner") = {1};
