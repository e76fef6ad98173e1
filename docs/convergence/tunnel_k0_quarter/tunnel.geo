// The jointed tunnel of tests/initial_stage.rs (TUNNEL_GEO): a circular
// opening, R = 2 m, in a 16 x 4 x 16 m box of rock (OpenCASCADE, tet10);
// the joint sets are cut by the scenes ([[joint_sets]]).
SetFactory("OpenCASCADE");
W = 16; L = 4; H = 16; R = 2;
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
MeshSize{ PointsOf{ Volume{1}; } } = 4.0;
MeshSize{ PointsOf{ Surface{wall()}; } } = 1.5;
Mesh.HighOrderOptimize = 2;
