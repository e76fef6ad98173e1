// tee2d.geo -- a 20 m gravity dam on a slab of jointed rock: two steep
// joints cut the slab and meet the sheeting joint under it, and the
// downstream one meets the dam's base, at T-junctions (three blocks, three
// pairs of one node copy each). The junction test of tests/junctions.rs.
//
//   y                      crest (2.5, 20)
//  20 +--+
//     |   \                upstream face x = 0 (water)
//     |dam \               base: y = 0, 0 <= x <= 15
//   0 +-----+-------+      steep: dip 75 deg, from (xa, 0) and (xj, 0)
//  ---/----/----------     down to the sheet at y = -ds
//    /    /   slab         sheet: y = -ds, the whole width
//  -------------------
//         deep rock        bottom y = -12 fixed, sides x = -15, 30 on rollers
//
SetFactory("OpenCASCADE");
DefineConstant[ lc = {1.0, Name "Parameters/element size"} ];
DefineConstant[ xj = {3.0, Name "Parameters/where the steep joint meets the base"} ];
DefineConstant[ xa = {-1.3, Name "Parameters/the steep joint upstream of the heel"} ];
DefineConstant[ ds = {2.5, Name "Parameters/the slab's depth"} ];
DefineConstant[ dip = {75.0, Name "Parameters/the steep joints' dip (degrees)"} ];
H = 20; B = 15; bc = 2.5; L1 = -15; L2 = 30; D = 12;
Point(1) = {0, 0, 0}; Point(2) = {B, 0, 0}; Point(3) = {bc, H, 0}; Point(4) = {0, H, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Rectangle(2) = {L1, -D, 0, L2 - L1, D};
h = ds / Tan(dip * Pi / 180);
Point(11) = {xj, 0, 0}; Point(12) = {xj - h, -ds, 0}; Line(11) = {11, 12};
Point(13) = {xa, 0, 0}; Point(14) = {xa - h, -ds, 0}; Line(12) = {13, 14};
Point(15) = {L1, -ds, 0}; Point(16) = {L2, -ds, 0}; Line(13) = {15, 16};
BooleanFragments{ Surface{1, 2}; Delete; }{ Curve{11, 12, 13}; Delete; }
Mesh.CharacteristicLengthMax = lc;
e = 1e-3;
Physical Surface("dam") = Surface In BoundingBox{-e, -e, -e, B + e, H + e, e};
Physical Surface("rock") = Surface In BoundingBox{L1 - e, -D - e, -e, L2 + e, e, e};
Physical Curve("base") = Curve In BoundingBox{-e, -e, -e, B + e, e, e};
steep() = Curve In BoundingBox{xj - h - e, -ds - e, -e, xj + e, e, e};
steep() += Curve In BoundingBox{xa - h - e, -ds - e, -e, xa + e, e, e};
Physical Curve("steep") = {steep()};
Physical Curve("sheet") = Curve In BoundingBox{L1 - e, -ds - e, -e, L2 + e, -ds + e, e};
Physical Curve("upstream_face") = Curve In BoundingBox{-e, -e, -e, e, H + e, e};
Physical Curve("bottom") = Curve In BoundingBox{L1 - e, -D - e, -e, L2 + e, -D + e, e};
Physical Curve("sides") = Curve In BoundingBox{L1 - e, -D - e, -e, L1 + e, e, e};
Physical Curve("sides") += Curve In BoundingBox{L2 - e, -D - e, -e, L2 + e, e, e};
