// slope3d.geo -- a rock slope in 3D: a 20 m face at 60 degrees (dip
// direction 180, facing -y) above a 10 m floor, 30 m along strike. The
// profile is drawn in the y-z plane and extruded along x. The joint sets
// are cut by the tool ([[joint_sets]] in the scene).
SetFactory("OpenCASCADE");
DefineConstant[ lc = {2.5, Name "Parameters/element size at the face"} ];
DefineConstant[ lc_far = {6.0, Name "Parameters/element size at the box"} ];
L = 30; D = 40; T = 10; Hf = 20; face = 60;
yc = T + Hf / Tan(face * Pi / 180);   // crest, 11.5 m behind the toe
Point(1) = {0, 0, 0};  Point(2) = {0, D, 0};  Point(3) = {0, D, T + Hf};
Point(4) = {0, yc, T + Hf};  Point(5) = {0, T, T};  Point(6) = {0, 0, T};
For i In {1:6}
  Line(i) = {i, i % 6 + 1};
EndFor
Curve Loop(1) = {1:6};
Plane Surface(1) = {1};
v() = Extrude{L, 0, 0}{ Surface{1}; };
e = 1e-3;
Physical Volume("rock") = {v(1)};
Physical Surface("base") = Surface In BoundingBox{-e, -e, -e, L + e, D + e, e};
Physical Surface("back") = Surface In BoundingBox{-e, D - e, -e, L + e, D + e, T + Hf + e};
Physical Surface("front") = Surface In BoundingBox{-e, -e, -e, L + e, e, T + e};
Physical Surface("sides") = Surface In BoundingBox{-e, -e, -e, e, D + e, T + Hf + e};
Physical Surface("sides") += Surface In BoundingBox{L - e, -e, -e, L + e, D + e, T + Hf + e};
Physical Surface("face") = Surface In BoundingBox{-e, T - e, T - e, L + e, yc + e, T + Hf + e};
MeshSize{ PointsOf{ Volume{v(1)}; } } = lc_far;
MeshSize{ PointsOf{ Surface{Surface In BoundingBox{-e, T - e, T - e, L + e, yc + e, T + Hf + e}}; } } = lc;
