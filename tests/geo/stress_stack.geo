// stress_stack.geo -- two blocks of w x h stacked along the local y axis,
// in contact along the local line y = h, placed anywhere on the map: the
// local frame is rotated by `angle` degrees and its origin moved to
// (x0, y0). The stress tests of tests/stress.rs use it for stretched
// elements (w/nx against h/ny), map coordinates and units.
//
//   local y
//   |   top (loads on "top_face")
// 2h +-----------+ 
//    |   top     |
//  h +-----------+   "joint" (shared curve, one node set)
//    |  bottom   |
//  0 +-----------+-- local x   "base": y = 0; "corner": (0, 0);
//    0           w             "left": x = 0 (both blocks)
//
// Structured meshes only (transfinite, nx by ny per block): quad = 1
// quadrilaterals, quad = 0 the same grid cut into triangles; so the mesh
// of a moved model is the moved mesh. serendipity = 1: quad8 for order 2.

DefineConstant[ w = {2, Name "Parameters/width"} ];
DefineConstant[ h = {1, Name "Parameters/height of a block"} ];
DefineConstant[ nx = {4, Name "Parameters/divisions along x"} ];
DefineConstant[ ny = {4, Name "Parameters/divisions along y per block"} ];
DefineConstant[ quad = {1, Name "Parameters/quadrilaterals"} ];
DefineConstant[ serendipity = {0, Name "Parameters/quad8 instead of quad9"} ];
DefineConstant[ x0 = {0, Name "Parameters/map x of the local origin"} ];
DefineConstant[ y0 = {0, Name "Parameters/map y of the local origin"} ];
DefineConstant[ angle = {0, Name "Parameters/rotation of the local frame, degrees"} ];
Mesh.SecondOrderIncomplete = serendipity;

ca = Cos(angle * Pi / 180);
sa = Sin(angle * Pi / 180);
If (angle == 0)
  ca = 1;
  sa = 0;
EndIf
lx[] = {0, w, w, 0, w, 0};
ly[] = {0, 0, h, h, 2 * h, 2 * h};
For i In {0 : 5}
  Point(i + 1) = {x0 + ca * lx[i] - sa * ly[i], y0 + sa * lx[i] + ca * ly[i], 0};
EndFor

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

Transfinite Curve{1, 3, 6} = nx + 1;
Transfinite Curve{2, 4, 5, 7} = ny + 1;
Transfinite Surface{1, 2};
If (quad)
  Recombine Surface{1, 2};
EndIf

Physical Surface("bottom") = {1};
Physical Surface("top") = {2};
Physical Curve("joint") = {3};
Physical Curve("base") = {1};
Physical Curve("top_face") = {6};
Physical Curve("left") = {4, 7};
Physical Point("corner") = {1};
