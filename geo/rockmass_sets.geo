// rockmass_sets.geo -- a 10 m cube of rock, each face a group. The joint
// sets that cut it into blocks are in geo/rockmass_sets.toml ([[joint_sets]]):
// the tool cuts the cube and names the pieces; "top" stays "top".
//
// Sample run:  subcontact solve geo/rockmass_sets.toml   (make rockmass)
SetFactory("OpenCASCADE");
DefineConstant[ L = {10.0, Name "Parameters/edge of the cube"} ];
DefineConstant[ lc = {1.25, Name "Parameters/element size"} ];
Box(1) = {0, 0, 0, L, L, L};
MeshSize{ PointsOf{ Volume{1}; } } = lc;
e = 1e-3;
Physical Volume("rock") = {1};
Physical Surface("base") = Surface In BoundingBox{-e, -e, -e, L + e, L + e, e};
Physical Surface("top") = Surface In BoundingBox{-e, -e, L - e, L + e, L + e, L + e};
Physical Surface("x0") = Surface In BoundingBox{-e, -e, -e, e, L + e, L + e};
Physical Surface("x1") = Surface In BoundingBox{L - e, -e, -e, L + e, L + e, L + e};
Physical Surface("y0") = Surface In BoundingBox{-e, -e, -e, L + e, e, L + e};
Physical Surface("y1") = Surface In BoundingBox{-e, L - e, -e, L + e, L + e, L + e};
