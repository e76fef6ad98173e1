// contact_stack3d.geo -- two boxes stacked along y (the 2D stack of
// contact_stack.geo extruded over z = 0..d), in contact on the plane y = h.
//
//   y
//   |    +-----------+
// 2h +---+-------+   |   top       "top_face": y = 2h
//    |   top     |   +
//  h +-----------+   |   "joint": y = h (shared surface, one node set)
//    |  bottom   |   +
//  0 +-----------+-- x   "base": y = 0; "x0": x = 0 (both boxes);
//    0           w        "z_faces": z = 0 and z = d (both boxes)
//
// hex = 1: hexahedra (transfinite, n x n x nz per box); hex = 0:
// unstructured tetrahedra of about the same size.

DefineConstant[ n = {3, Name "Parameters/divisions per edge"} ];
DefineConstant[ nz = {2, Name "Parameters/divisions through z"} ];
DefineConstant[ hex = {1, Name "Parameters/hexahedra"} ];
DefineConstant[ serendipity = {0, Name "Parameters/hex20 instead of hex27"} ];
Mesh.SecondOrderIncomplete = serendipity;
w = 2.0;
h = 1.0;
d = 1.0;
lc = w / n;   // element size of the tetrahedra

Point(1) = {0, 0, 0, lc};
Point(2) = {w, 0, 0, lc};
Point(3) = {w, h, 0, lc};
Point(4) = {0, h, 0, lc};
Point(5) = {w, 2 * h, 0, lc};
Point(6) = {0, 2 * h, 0, lc};

Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Line(5) = {3, 5};
Line(6) = {5, 6};
Line(7) = {6, 4};

Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Curve Loop(2) = {-3, 5, 6, 7};
Plane Surface(2) = {2};

If (hex)
  Transfinite Curve{1, 3, 6} = n + 1;
  Transfinite Curve{2, 4, 5, 7} = n + 1 Using Progression 1.3;
  Transfinite Surface{1, 2};
  Recombine Surface{1, 2};
  out1[] = Extrude {0, 0, d} { Surface{1}; Layers{nz}; Recombine; };
  out2[] = Extrude {0, 0, d} { Surface{2}; Layers{nz}; Recombine; };
Else
  out1[] = Extrude {0, 0, d} { Surface{1}; };
  out2[] = Extrude {0, 0, d} { Surface{2}; };
EndIf
// out[0] top, out[1] volume, out[2..5] the sides from curves 1,2,3,4 (resp. -3,5,6,7)

Physical Volume("bottom") = {out1[1]};
Physical Volume("top") = {out2[1]};
Physical Surface("joint") = {out1[4]};
Physical Surface("base") = {out1[2]};
Physical Surface("top_face") = {out2[4]};
Physical Surface("x0") = {out1[5], out2[5]};
Physical Surface("z_faces") = {1, 2, out1[0], out2[0]};
