// tunnel_joints.geo -- a circular tunnel in rock (2D, plane strain): a
// 30 m x 30 m box minus the opening. The three joint sets that cut the
// rock into blocks are in geo/tunnel_joints.toml ([[joint_sets]]): the tool
// lays their traces, cuts the rock and names the pieces.
//
//   y                                      sets (angle from x, spacing,
//   15 +-------------------------------+     offset of a trace from the
//      |  /    /  `-.  /    /    /     |     centre, measured along the
//      |-/----/------`/-.--/----/------|     set's normal (-sin, cos)):
//      |/    /       /   `-.   /       |   bedding    0 deg, 3 m, 1.5 m
//      /    /    .--/--.   /`-.        |   joints_a  60 deg, 4 m, 3.5 m
//      |---/----/--/----\-/-----`-.----|   joints_b 150 deg, 6 m, 2.5 m
//      |  /    | (  R = 3 m )  /    /  |
//      | /     /  `------'   /    /    |   "wall": the opening r = R
//    0 |/-----/------/------/----/-----|   "top": y = 15, "bottom": y = -15,
//      |    ...                        |   "sides": x = -15 and x = 15
//  -15 +-------------------------------+-- x
//    -15               0               15
//
// Sample run:  subcontact solve geo/tunnel_joints.toml   (make tunnel-joints)
SetFactory("OpenCASCADE");
DefineConstant[ lc = {0.6, Min 0.1, Max 3, Name "Parameters/element size at the opening"} ];
DefineConstant[ lc_far = {2.0, Min 0.5, Max 6, Name "Parameters/element size at the box"} ];
DefineConstant[ W = {15, Min 6, Max 60, Name "Parameters/half width of the box"} ];
R = 3;
Rectangle(1) = {-W, -W, 0, 2 * W, 2 * W};
Disk(2) = {0, 0, 0, R};
BooleanDifference{ Surface{1}; Delete; }{ Surface{2}; Delete; }
e = 1e-3;
Physical Surface("rock") = {1};
wall() = Curve In BoundingBox{-R - e, -R - e, -e, R + e, R + e, e};
Physical Curve("wall") = {wall()};
Physical Curve("top") = Curve In BoundingBox{-W - e, W - e, -e, W + e, W + e, e};
Physical Curve("bottom") = Curve In BoundingBox{-W - e, -W - e, -e, W + e, -W + e, e};
Physical Curve("sides") = Curve In BoundingBox{-W - e, -W - e, -e, -W + e, W + e, e};
Physical Curve("sides") += Curve In BoundingBox{W - e, -W - e, -e, W + e, W + e, e};
MeshSize{ PointsOf{ Surface{1}; } } = lc_far;
MeshSize{ PointsOf{ Curve{wall()}; } } = lc;
