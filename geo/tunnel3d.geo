// tunnel3d.geo -- a circular tunnel, R = 3 m, along y through a 24 x 12 x 24 m
// box of rock. The three joint sets that cut the rock into blocks are in
// geo/tunnel3d.toml ([[joint_sets]]: dip / dip direction, spacing, offset):
// the tool lays their planes, cuts the rock and names the pieces.
// Groups: "rock"; "top" z = 12, "bottom" z = -12, "sides" x = -12 and 12,
// "ends" y = 0 and 12, "wall" the opening r = R.
// Sample run:  subcontact solve geo/tunnel3d.toml   (make tunnel3d)
SetFactory("OpenCASCADE");
DefineConstant[ lc = {2.0, Min 0.3, Max 5, Name "Parameters/element size at the opening"} ];
DefineConstant[ lc_far = {4.0, Min 0.5, Max 10, Name "Parameters/element size at the box"} ];
W = 24; L = 12; H = 24; R = 3;
Box(1) = {-W / 2, 0, -H / 2, W, L, H};
Cylinder(2) = {0, -1, 0, 0, L + 2, 0, R};
BooleanDifference{ Volume{1}; Delete; }{ Volume{2}; Delete; }
e = 1e-3;
Physical Volume("rock") = {1};
Physical Surface("top") = Surface In BoundingBox{-W / 2 - e, -e, H / 2 - e, W / 2 + e, L + e, H / 2 + e};
Physical Surface("bottom") = Surface In BoundingBox{-W / 2 - e, -e, -H / 2 - e, W / 2 + e, L + e, -H / 2 + e};
Physical Surface("sides") = Surface In BoundingBox{-W / 2 - e, -e, -H / 2 - e, -W / 2 + e, L + e, H / 2 + e};
Physical Surface("sides") += Surface In BoundingBox{W / 2 - e, -e, -H / 2 - e, W / 2 + e, L + e, H / 2 + e};
Physical Surface("ends") = Surface In BoundingBox{-W / 2 - e, -e, -H / 2 - e, W / 2 + e, e, H / 2 + e};
Physical Surface("ends") += Surface In BoundingBox{-W / 2 - e, L - e, -H / 2 - e, W / 2 + e, L + e, H / 2 + e};
wall() = Surface In BoundingBox{-R - e, -e, -R - e, R + e, L + e, R + e};
Physical Surface("wall") = {wall()};
MeshSize{ PointsOf{ Volume{1}; } } = lc_far;
MeshSize{ PointsOf{ Surface{wall()}; } } = lc;
Mesh.HighOrderOptimize = 2;      // no tet10 folded where the joints meet the curved wall
