// stack.geo -- three blocks stacked on a held base, two horizontal joints
// between them: a weak upper joint (a cracked lift joint, small tensile
// strength) and a strong lower one. The top block is anchored at both
// sides and pulled up at its top face: the upper joint opens over its whole
// length, the top block hangs on its anchors, and the middle block rests on
// the lower joint, which stays stuck and carries exactly its weight.
//
// Sample runs:
//   subcontact solve geo/stack.toml                    (quad9, lc = 0.25)
//   setnumber = { lc = 0.1 } in stack.toml             (a finer mesh)
//
//     y         top_face (pulled up)
//   3h +------------------+
//      |       top        |  anchor: both sides of the top block, held in x and y
//   2h +== upper_joint ===+  weak: opens
//      |      middle      |  free sides
//    h +== lower_joint ===+  strong: sticks, carries the middle block's weight
//      |      bottom      |
//    0 +------------------+-- x
//     0      base (held)  w
//
// Blocks w = 2 wide, h = 1 high, structured quadrilaterals of size lc.

DefineConstant[ lc = {0.25, Min 0.01, Max 1, Name "Parameters/element size"} ];
w = 2.0;
h = 1.0;

// 1. Four horizontal lines (y = 0, h, 2h, 3h) and the blocks' sides.
For i In {0:3}
  Point(1 + 2 * i) = {0, i * h, 0};
  Point(2 + 2 * i) = {w, i * h, 0};
  Line(1 + i) = {1 + 2 * i, 2 + 2 * i};
EndFor
For i In {0:2}
  Line(5 + 2 * i) = {2 + 2 * i, 4 + 2 * i};   // right side of block i
  Line(6 + 2 * i) = {1 + 2 * i, 3 + 2 * i};   // left side of block i
  Curve Loop(1 + i) = {1 + i, 5 + 2 * i, -(2 + i), -(6 + 2 * i)};
  Plane Surface(1 + i) = {1 + i};
EndFor

// 2. Structured quadrilaterals, node to node across the joints.
Transfinite Curve{1:4} = Ceil(w / lc) + 1;
Transfinite Curve{5:10} = Ceil(h / lc) + 1;
Transfinite Surface{1:3};
Recombine Surface{1:3};

Physical Surface("bottom") = {1};
Physical Surface("middle") = {2};
Physical Surface("top") = {3};
Physical Curve("lower_joint") = {2};
Physical Curve("upper_joint") = {3};
Physical Curve("base") = {1};
Physical Curve("top_face") = {4};
Physical Curve("anchor") = {9, 10};
