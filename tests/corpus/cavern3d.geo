// cavern3d.geo -- a cavern 10 m wide, 12 m high (vertical walls 7 m, a
// semicircular roof of radius 5 m), 12 m long, in a 40 x 12 x 40 m box of
// rock. The joint sets are cut by the tool ([[joint_sets]] in the scene).
SetFactory("OpenCASCADE");
DefineConstant[ lc = {3.0, Name "Parameters/element size at the cavern"} ];
DefineConstant[ lc_far = {8.0, Name "Parameters/element size at the box"} ];
W = 40; L = 12; H = 40; B = 10; hw = 7; R = B / 2;
Box(1) = {-W / 2, 0, -H / 2, W, L, H};
Box(2) = {-R, -1, -6, B, L + 2, hw};
Cylinder(3) = {0, -1, -6 + hw, 0, L + 2, 0, R};
BooleanUnion(4) = { Volume{2}; Delete; }{ Volume{3}; Delete; };
BooleanDifference(5) = { Volume{1}; Delete; }{ Volume{4}; Delete; };
e = 1e-3;
Physical Volume("rock") = {5};
Physical Surface("outer") = Surface In BoundingBox{-W / 2 - e, -e, -H / 2 - e, -W / 2 + e, L + e, H / 2 + e};
Physical Surface("outer") += Surface In BoundingBox{W / 2 - e, -e, -H / 2 - e, W / 2 + e, L + e, H / 2 + e};
Physical Surface("outer") += Surface In BoundingBox{-W / 2 - e, -e, -H / 2 - e, W / 2 + e, L + e, -H / 2 + e};
Physical Surface("outer") += Surface In BoundingBox{-W / 2 - e, -e, H / 2 - e, W / 2 + e, L + e, H / 2 + e};
Physical Surface("ends") = Surface In BoundingBox{-W / 2 - e, -e, -H / 2 - e, W / 2 + e, e, H / 2 + e};
Physical Surface("ends") += Surface In BoundingBox{-W / 2 - e, L - e, -H / 2 - e, W / 2 + e, L + e, H / 2 + e};
wall() = Surface In BoundingBox{-R - e, -e, -6 - e, R + e, L + e, -6 + hw + R + e};
Physical Surface("cavern") = {wall()};
MeshSize{ PointsOf{ Volume{5}; } } = lc_far;
MeshSize{ PointsOf{ Surface{wall()}; } } = lc;
