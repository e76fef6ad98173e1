// dam.geo -- a gravity dam of three blocks separated by vertical joints, on
// a rock foundation, under self-weight and a full reservoir. The joints and
// the dam–rock base are contacts; the base and the joints carry no tension,
// so the heel (the upstream end of the base) opens under the reservoir.
//
// Sample run:
//   subcontact solve geo/dam.toml        (make dam)
//
//   water  |  \
//   level  | b1 \                 H = 50 m, crest 5 m, base B = 28 m,
//   ~~~~~~ |    |\                joints at x = 9 and x = 18
//   water  |    | \
//   pushes | b1 |b2\
//   here   |    |   |\
//          |    |   | b3\
//   =======+====+===+====+=========  base (contact), rock below
//   rock (massless foundation, 150 m x 60 m, held at the bottom and sides)
//
// Where the joints meet the base, the two blocks stay joined at that one
// node, which pairs with the rock (contacts meet only where one ends).

DefineConstant[ lc = {1.0, Min 0.1, Max 5, Name "Parameters/element size in the dam"} ];
DefineConstant[ lc_rock = {8.0, Min 0.5, Max 20, Name "Parameters/element size far in the rock"} ];
H = 50; crest = 5; B = 28; j1 = 9; j2 = 18;
yd1 = H * (B - j1) / (B - crest);   // downstream face height at the joints
yd2 = H * (B - j2) / (B - crest);

// dam
Point(1) = {0, 0, 0, lc};
Point(2) = {j1, 0, 0, lc};
Point(3) = {j2, 0, 0, lc};
Point(4) = {B, 0, 0, lc};
Point(5) = {j2, yd2, 0, lc};
Point(6) = {j1, yd1, 0, lc};
Point(7) = {crest, H, 0, lc};
Point(8) = {0, H, 0, lc};
// rock
Point(10) = {-60, 0, 0, lc_rock};
Point(11) = {-60, -60, 0, lc_rock};
Point(12) = {90, -60, 0, lc_rock};
Point(13) = {90, 0, 0, lc_rock};

Line(1) = {1, 2};    // base under block 1
Line(2) = {2, 3};    // base under block 2
Line(3) = {3, 4};    // base under block 3
Line(4) = {4, 5};    // downstream face of block 3
Line(5) = {5, 3};    // joint 2-3
Line(6) = {5, 6};    // downstream face of block 2
Line(7) = {6, 2};    // joint 1-2
Line(8) = {6, 7};    // downstream face of block 1
Line(9) = {7, 8};    // crest
Line(10) = {8, 1};   // upstream face
Line(11) = {10, 1};  // reservoir floor
Line(12) = {10, 11};
Line(13) = {11, 12};
Line(14) = {12, 13};
Line(15) = {13, 4};  // downstream ground

Curve Loop(1) = {1, -7, 8, 9, 10};
Plane Surface(1) = {1};
Curve Loop(2) = {2, -5, 6, 7};
Plane Surface(2) = {2};
Curve Loop(3) = {3, 4, 5};
Plane Surface(3) = {3};
Curve Loop(4) = {12, 13, 14, 15, -3, -2, -1, -11};
Plane Surface(4) = {4};

Physical Surface("block_1") = {1};
Physical Surface("block_2") = {2};
Physical Surface("block_3") = {3};
Physical Surface("rock") = {4};
Physical Curve("base") = {1, 2, 3};
Physical Curve("joint_12") = {7};
Physical Curve("joint_23") = {5};
Physical Curve("upstream_face") = {10};
Physical Curve("reservoir_floor") = {11};
Physical Curve("rock_bottom") = {13};
Physical Curve("rock_sides") = {12, 14};
