// dam2d.geo -- a 40 m gravity dam in two lifts on a rock foundation. The
// dam's upstream face is vertical (x = 0); the lift joint is at y = 15 m.
// The foundation's joints are cut by the tool ([[joint_sets]] in the
// scene); the base and the lift joint are groups of their own.
SetFactory("OpenCASCADE");
DefineConstant[ lc = {2.5, Name "Parameters/element size"} ];
DefineConstant[ lc_far = {6.0, Name "Parameters/element size far in the rock"} ];
H = 40; B = 30; bc = 5; hl = 15;
xl = B - (B - bc) * hl / H;      // the downstream face at the lift joint
Point(1) = {0, 0, 0}; Point(2) = {B, 0, 0}; Point(3) = {xl, hl, 0}; Point(4) = {0, hl, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};          // the lower lift
Point(5) = {0, hl, 0}; Point(6) = {xl, hl, 0}; Point(7) = {bc, H, 0}; Point(8) = {0, H, 0};
Line(5) = {5, 6}; Line(6) = {6, 7}; Line(7) = {7, 8}; Line(8) = {8, 5};
Curve Loop(2) = {5, 6, 7, 8};
Plane Surface(2) = {2};          // the upper lift
Rectangle(3) = {-35, -30, 0, 100, 30};   // the foundation
BooleanFragments{ Surface{1, 2, 3}; Delete; }{}
e = 1e-3;
Physical Surface("lower_lift") = {1};
Physical Surface("upper_lift") = {2};
Physical Surface("foundation") = {3};
Physical Curve("base") = Curve In BoundingBox{-e, -e, -e, B + e, e, e};
Physical Curve("lift_joint") = Curve In BoundingBox{-e, hl - e, -e, xl + e, hl + e, e};
Physical Curve("upstream_face") = Curve In BoundingBox{-e, -e, -e, e, H + e, e};
Physical Curve("bottom") = Curve In BoundingBox{-35 - e, -30 - e, -e, 65 + e, -30 + e, e};
Physical Curve("sides") = Curve In BoundingBox{-35 - e, -30 - e, -e, -35 + e, e, e};
Physical Curve("sides") += Curve In BoundingBox{65 - e, -30 - e, -e, 65 + e, e, e};
MeshSize{ PointsOf{ Surface{:}; } } = lc_far;
MeshSize{ PointsOf{ Surface{1, 2}; } } = lc;
