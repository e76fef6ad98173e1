// tunnel4sets.geo -- a circular tunnel (R = 3 m) along y
// through a 30 x 10 x 30 m box of rock, centre 60 m deep. The four joint
// sets are cut by the tool ([[joint_sets]] in tunnel4sets.toml).
SetFactory("OpenCASCADE");
DefineConstant[ lc = {2.5, Name "Parameters/element size at the tunnel"} ];
DefineConstant[ lc_far = {7.0, Name "Parameters/element size at the box"} ];
W = 30; L = 10; H = 30; R = 3;
Box(1) = {-W / 2, 0, -H / 2, W, L, H};
Cylinder(2) = {0, -1, 0, 0, L + 2, 0, R};
BooleanDifference(3) = { Volume{1}; Delete; }{ Volume{2}; Delete; };
e = 1e-3;
Physical Volume("rock") = {3};
Physical Surface("top") = Surface In BoundingBox{-W / 2 - e, -e, H / 2 - e, W / 2 + e, L + e, H / 2 + e};
Physical Surface("bottom") = Surface In BoundingBox{-W / 2 - e, -e, -H / 2 - e, W / 2 + e, L + e, -H / 2 + e};
Physical Surface("west") = Surface In BoundingBox{-W / 2 - e, -e, -H / 2 - e, -W / 2 + e, L + e, H / 2 + e};
Physical Surface("east") = Surface In BoundingBox{W / 2 - e, -e, -H / 2 - e, W / 2 + e, L + e, H / 2 + e};
Physical Surface("south") = Surface In BoundingBox{-W / 2 - e, -e, -H / 2 - e, W / 2 + e, e, H / 2 + e};
Physical Surface("north") = Surface In BoundingBox{-W / 2 - e, L - e, -H / 2 - e, W / 2 + e, L + e, H / 2 + e};
wall() = Surface In BoundingBox{-R - e, -e, -R - e, R + e, L + e, R + e};
Physical Surface("wall") = {wall()};
MeshSize{ PointsOf{ Volume{3}; } } = lc_far;
MeshSize{ PointsOf{ Surface{wall()}; } } = lc;
Mesh.HighOrderOptimize = 2;      // quadratic elements on the curved wall: none folded
