// dam3d_joints.geo -- a gravity dam of three monoliths in a stepped valley:
// transverse contraction joints (y = 10, 20) between the monoliths. The lift
// joints (z = 20, 35) that cross them are not here: they are a joint set of
// geo/dam3d_joints.toml ([[joint_sets]] "lifts", horizontal, 15 m apart),
// which the tool cuts into the monoliths, so four blocks meet along every
// crossing line. OpenCASCADE volumes joined by BooleanFragments: every
// shared face is meshed once.
//
//   section (x, z), every monolith          elevation from upstream (y, z)
//     z                                       z
//  50 +--+  crest 5 m                      50 +---------+---------+---------+
//     |  |\                                   |  left   | middle  |  right  |
//  35 +--+-\--- lift joint (the scene)     35 +- lifts -+---------+---------+
//     |     \                                 |         |         |         |
//  20 +------\-- lift joint (the scene)    20 +---------+---------+---------+
//     | dam   \                               |         |         |         |
//   0 +--------+--- base 28 m              10 +=========+         +=========+
//     |  rock (x -40..70, z -40..0,           |  rock   |         |  rock   |
//     |  steps z 0..10 under the sides)     0 +=========+=========+=========+
//                                             0        10        20        30  y
//
// Groups: "left", "middle", "right" (the monoliths), "rock"; "base" (every
// face between the dam and the rock, the steps' sides included),
// "contraction" (y = 10 and 20 above the steps); "upstream_face" (x = 0,
// the dam), "reservoir_floor" (the rock's top upstream), "rock_bottom",
// "rock_ends" (x = -40 and 70), "rock_sides" (y = 0 and 30). The
// reservoir's floor includes the steps' sides upstream of the dam.
//
// Sample run:  subcontact solve geo/dam3d_joints.toml   (make dam3d-joints)
SetFactory("OpenCASCADE");
DefineConstant[ lc = {4.0, Min 0.5, Max 10, Name "Parameters/element size in the dam"} ];
DefineConstant[ lc_rock = {15.0, Min 1, Max 40, Name "Parameters/element size far in the rock"} ];
H = 50; crest = 5; B = 28;        // the dam's section
L = 30; y1 = 10; y2 = 20;          // its length and the contraction joints
step = 10;                         // the valley's steps under the side monoliths
X0 = -40; X1 = 70; D = 40;         // the rock

// 1. The monoliths: the section x = B - (B - crest) z / H above its base,
// extruded over its width.
ys[] = {0, y1, y2, L};
bases[] = {step, 0, step};
For m In {0:2}
  za = bases[m];
  p1 = newp; Point(p1) = {0, ys[m], za};
  p2 = newp; Point(p2) = {B - (B - crest) * za / H, ys[m], za};
  p3 = newp; Point(p3) = {crest, ys[m], H};
  p4 = newp; Point(p4) = {0, ys[m], H};
  c1 = newc; Line(c1) = {p1, p2};
  c2 = newc; Line(c2) = {p2, p3};
  c3 = newc; Line(c3) = {p3, p4};
  c4 = newc; Line(c4) = {p4, p1};
  cl = newll; Curve Loop(cl) = {c1, c2, c3, c4};
  s = news; Plane Surface(s) = {cl};
  ext[] = Extrude {0, ys[m + 1] - ys[m], 0} { Surface{s}; };
  mono[m] = ext[1];
EndFor
left() = {mono[0]}; middle() = {mono[1]}; right() = {mono[2]};

// 2. The rock: a box and the two steps of the valley.
rk = newv; Box(rk) = {X0, 0, -D, X1 - X0, L, D};
st1 = newv; Box(st1) = {X0, 0, 0, X1 - X0, y1, step};
st2 = newv; Box(st2) = {X0, y2, 0, X1 - X0, L - y2, step};
BooleanFragments{ Volume{left(), middle(), right(), rk, st1, st2}; Delete; }{}

// 3. Groups. (OCC enlarges bounding boxes: selections need a margin.)
e = 1e-3;
Physical Volume("left") = {left()};
Physical Volume("middle") = {middle()};
Physical Volume("right") = {right()};
Physical Volume("rock") = {rk, st1, st2};
base() = Surface In BoundingBox{-e, y1 - e, -e, B + e, y2 + e, e};
base() += Surface In BoundingBox{-e, -e, step - e, B + e, y1 + e, step + e};
base() += Surface In BoundingBox{-e, y2 - e, step - e, B + e, L + e, step + e};
base() += Surface In BoundingBox{-e, y1 - e, -e, B + e, y1 + e, step + e};
base() += Surface In BoundingBox{-e, y2 - e, -e, B + e, y2 + e, step + e};
Physical Surface("base") = {base()};
Physical Surface("contraction") = Surface In BoundingBox{-e, y1 - e, step - e, B + e, y1 + e, H + e};
Physical Surface("contraction") += Surface In BoundingBox{-e, y2 - e, step - e, B + e, y2 + e, H + e};
Physical Surface("upstream_face") = Surface In BoundingBox{-e, -e, -e, e, L + e, H + e};
// the reservoir's floor: the rock's top and the steps' sides upstream
floor() = Surface In BoundingBox{X0 - e, y1 - e, -e, e, y2 + e, e};
floor() += Surface In BoundingBox{X0 - e, -e, step - e, e, y1 + e, step + e};
floor() += Surface In BoundingBox{X0 - e, y2 - e, step - e, e, L + e, step + e};
floor() += Surface In BoundingBox{X0 - e, y1 - e, -e, e, y1 + e, step + e};
floor() += Surface In BoundingBox{X0 - e, y2 - e, -e, e, y2 + e, step + e};
Physical Surface("reservoir_floor") = {floor()};
Physical Surface("rock_bottom") = Surface In BoundingBox{X0 - e, -e, -D - e, X1 + e, L + e, -D + e};
Physical Surface("rock_ends") = Surface In BoundingBox{X0 - e, -e, -D - e, X0 + e, L + e, step + e};
Physical Surface("rock_ends") += Surface In BoundingBox{X1 - e, -e, -D - e, X1 + e, L + e, step + e};
Physical Surface("rock_sides") = Surface In BoundingBox{X0 - e, -e, -D - e, X1 + e, e, step + e};
Physical Surface("rock_sides") += Surface In BoundingBox{X0 - e, L - e, -D - e, X1 + e, L + e, step + e};

// 4. Sizes: lc in the dam, lc_rock far in the rock.
MeshSize{ PointsOf{ Volume{:}; } } = lc_rock;
MeshSize{ PointsOf{ Volume{left(), middle(), right()}; } } = lc;
