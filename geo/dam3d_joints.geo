// dam3d_joints.geo -- a gravity dam of three monoliths in a stepped valley,
// each monolith cut into lifts: transverse contraction joints (y = 10, 20)
// cross the horizontal lift joints (z = 20, 35), so four blocks meet along
// every crossing line. OpenCASCADE volumes joined by BooleanFragments:
// every shared face is meshed once, and the joints, the lift joints and the
// base are contact groups.
//
//   section (x, z), every monolith          elevation from upstream (y, z)
//     z                                       z
//  50 +--+  crest 5 m                      50 +---------+---------+---------+
//     |  |\                                   |  left   | middle  |  right  |
//  35 +--+-\--- lift joint                 35 +- lifts -+---------+---------+
//     |     \                                 |         |         |         |
//  20 +------\-- lift joint                20 +---------+---------+---------+
//     | dam   \                               |         |         |         |
//   0 +--------+--- base 28 m              10 +=========+         +=========+
//     |  rock (x -40..70, z -40..0,           |  rock   |         |  rock   |
//     |  steps z 0..10 under the sides)     0 +=========+=========+=========+
//                                             0        10        20        30  y
//
// Groups: "left", "middle", "right" (the monoliths, each cut into lifts by
// the lift joints), "dam" (all three), "rock"; "base" (every face between
// the dam and the rock, the steps' sides included), "contraction" (y = 10
// and 20 above the steps), "lifts" (z = 20 and 35); "upstream_face" (x = 0,
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
lifts[] = {20, 35};                // the lift joints
X0 = -40; X1 = 70; D = 40;         // the rock

// The downstream face: x = B - (B - crest) z / H.
Macro Lift
  // the section between z = za and zb, extruded over y = ya .. yb: vol
  xa = B - (B - crest) * za / H; xb = B - (B - crest) * zb / H;
  p1 = newp; Point(p1) = {0, ya, za};
  p2 = newp; Point(p2) = {xa, ya, za};
  p3 = newp; Point(p3) = {xb, ya, zb};
  p4 = newp; Point(p4) = {0, ya, zb};
  c1 = newc; Line(c1) = {p1, p2};
  c2 = newc; Line(c2) = {p2, p3};
  c3 = newc; Line(c3) = {p3, p4};
  c4 = newc; Line(c4) = {p4, p1};
  cl = newll; Curve Loop(cl) = {c1, c2, c3, c4};
  s = news; Plane Surface(s) = {cl};
  ext[] = Extrude {0, yb - ya, 0} { Surface{s}; };
  vol = ext[1];
Return

// 1. The monoliths, lift by lift (gmsh runs a Call at the end of its line).
ys[] = {0, y1, y2, L};
bases[] = {step, 0, step};
left() = {}; middle() = {}; right() = {};
For m In {0:2}
  zs[] = {bases[m], lifts[], H};
  For k In {0:#zs[] - 2}
    ya = ys[m]; yb = ys[m + 1]; za = zs[k]; zb = zs[k + 1];
    Call Lift;
    If (m == 0)
      left() += vol;
    ElseIf (m == 1)
      middle() += vol;
    Else
      right() += vol;
    EndIf
  EndFor
EndFor

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
Physical Volume("dam") = {left(), middle(), right()};
Physical Volume("rock") = {rk, st1, st2};
base() = Surface In BoundingBox{-e, y1 - e, -e, B + e, y2 + e, e};
base() += Surface In BoundingBox{-e, -e, step - e, B + e, y1 + e, step + e};
base() += Surface In BoundingBox{-e, y2 - e, step - e, B + e, L + e, step + e};
base() += Surface In BoundingBox{-e, y1 - e, -e, B + e, y1 + e, step + e};
base() += Surface In BoundingBox{-e, y2 - e, -e, B + e, y2 + e, step + e};
Physical Surface("base") = {base()};
Physical Surface("contraction") = Surface In BoundingBox{-e, y1 - e, step - e, B + e, y1 + e, H + e};
Physical Surface("contraction") += Surface In BoundingBox{-e, y2 - e, step - e, B + e, y2 + e, H + e};
lift() = {};
For k In {0:#lifts[] - 1}
  lift() += Surface In BoundingBox{-e, -e, lifts[k] - e, B + e, L + e, lifts[k] + e};
EndFor
Physical Surface("lifts") = {lift()};
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
