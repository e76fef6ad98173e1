// wedge_groove.geo -- a wedge in a V-groove that does not reach the
// groove's floor: the contact is the two faces dipping 45 degrees towards
// each other, with no crease between them (tests/contact3d.rs). The rock
// block [-2, 2] x [0, L] x [-1, 1] has a groove down to z = 0.3, its floor
// flat between x = -0.3 and 0.3; the wedge fills it down to z = 0.4.
//
//      z
//    1 +--+-----------+--+      "faces": the wedge's two sloping faces
//      |   \  wedge  /   |      against the rock's
//  0.4 |    \_______/    |
//  0.3 |     \_____/     |      (a gap of 0.1 under the wedge)
//      |                 |
//   -1 +-----------------+ x    "bottom" (z = -1)
//     -2                 2

SetFactory("OpenCASCADE");
DefineConstant[ lc = {0.3, Name "Parameters/element size"} ];
L = 2.0; e = 1e-3;
Point(1) = {-1, 0, 1}; Point(2) = {-0.3, 0, 0.3}; Point(3) = {0.3, 0, 0.3}; Point(4) = {1, 0, 1};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
groove[] = Extrude {0, L, 0} { Surface{1}; };
Point(11) = {-1, 0, 1}; Point(12) = {-0.4, 0, 0.4}; Point(13) = {0.4, 0, 0.4}; Point(14) = {1, 0, 1};
Line(21) = {11, 12}; Line(22) = {12, 13}; Line(23) = {13, 14}; Line(24) = {14, 11};
Curve Loop(21) = {21, 22, 23, 24}; Plane Surface(21) = {21};
w[] = Extrude {0, L, 0} { Surface{21}; };
Box(100) = {-2, 0, -1, 4, L, 2};
r() = BooleanDifference{ Volume{100}; Delete; }{ Volume{groove[1]}; Delete; };
all() = BooleanFragments{ Volume{r(), w[1]}; Delete; }{};
wedge() = Volume In BoundingBox{-1 - e, -e, 0.4 - e, 1 + e, L + e, 1 + e};
rk() = all(); rk() -= wedge();
Physical Volume("rock") = {rk()};
Physical Volume("wedge") = {wedge()};
Physical Surface("faces") = {Surface In BoundingBox{-1 - e, -e, 0.4 - e, -0.4 + e, L + e, 1 + e}, Surface In BoundingBox{0.4 - e, -e, 0.4 - e, 1 + e, L + e, 1 + e}};
Physical Surface("bottom") = {Surface In BoundingBox{-2 - e, -e, -1 - e, 2 + e, L + e, -1 + e}};
Mesh.CharacteristicLengthMax = lc;
