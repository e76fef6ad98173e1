// mech_blocks.geo -- two blocks stacked along the local y axis, in contact
// along the line y = h, the whole geometry turned by theta degrees about the
// origin; the contact patch test and the closing-gap case of tests/mechanics.rs.
//
//   local y
//   |        top_face
//  2h +-----------+
//     |   top     |  left_top / right_top: the top block's sides
//   h +===joint===+
//     |  bottom   |  left_bottom / right_bottom: the bottom block's sides
//   0 o-----------o-- local x
//    pin   base   roller
//
// Every side is its own physical curve so that the tractions sigma n of a
// uniform stress can be put on each; pin (0, 0) and roller (w, 0) are the
// points of a statically determinate support. quad = 1: transfinite
// quadrilaterals, uneven up the sides; quad = 0: unstructured triangles.
//
// pad = 1 adds a soft pad of height h/2 on top (bonded to the top block by
// the shared top face, its own top "pad_top"), from which the top block
// hangs when the joint opens; "top_face" is then inside and not a group.

DefineConstant[ n = {4, Name "Parameters/divisions along the joint"} ];
DefineConstant[ quad = {1, Name "Parameters/quadrilaterals"} ];
DefineConstant[ serendipity = {0, Name "Parameters/quad8 instead of quad9"} ];
DefineConstant[ theta = {0, Name "Parameters/rotation (degrees)"} ];
DefineConstant[ pad = {0, Name "Parameters/soft pad on top"} ];
Mesh.SecondOrderIncomplete = serendipity;
w = 2.0;
h = 1.0;

Point(1) = {0, 0, 0};
Point(2) = {w, 0, 0};
Point(3) = {w, h, 0};
Point(4) = {0, h, 0};
Point(5) = {w, 2 * h, 0};
Point(6) = {0, 2 * h, 0};

Line(1) = {1, 2};   // base
Line(2) = {2, 3};   // right_bottom
Line(3) = {3, 4};   // the joint
Line(4) = {4, 1};   // left_bottom
Line(5) = {3, 5};   // right_top
Line(6) = {5, 6};   // top face
Line(7) = {6, 4};   // left_top

Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Curve Loop(2) = {-3, 5, 6, 7};
Plane Surface(2) = {2};

Transfinite Curve{1, 3, 6} = n + 1;
Transfinite Curve{2, 4, 5, 7} = Ceil(n / 2) + 1 Using Progression 1.3;
If (quad)
  Transfinite Surface{1, 2};
  Recombine Surface{1, 2};
EndIf
Mesh.CharacteristicLengthMax = w / n;

If (pad)
  Point(7) = {w, 2.5 * h, 0};
  Point(8) = {0, 2.5 * h, 0};
  Line(8) = {5, 7};
  Line(9) = {7, 8};   // pad_top
  Line(10) = {8, 6};
  Curve Loop(3) = {-6, 8, 9, 10};
  Plane Surface(3) = {3};
  Transfinite Curve{9} = n + 1;
  Transfinite Curve{8, 10} = 2;
  If (quad)
    Transfinite Surface{3};
    Recombine Surface{3};
  EndIf
  Physical Surface("pad") = {3};
  Physical Curve("pad_top") = {9};
EndIf

Rotate {{0, 0, 1}, {0, 0, 0}, theta * Pi / 180} { Surface{:}; }

Physical Surface("bottom") = {1};
Physical Surface("top") = {2};
Physical Curve("joint") = {3};
Physical Curve("base") = {1};
If (!pad)
  Physical Curve("top_face") = {6};
EndIf
Physical Curve("left_bottom") = {4};
Physical Curve("right_bottom") = {2};
Physical Curve("left_top") = {7};
Physical Curve("right_top") = {5};
Physical Point("pin") = {1};
Physical Point("roller") = {2};
