// blocks3d.geo -- a stack of rock on a concrete slab: the rock is one box
// (10 x 6 x 6 m) that the joint sets of the scene cut into blocks; the
// slab below (12 x 8 x 1 m) is held; "west" is the rock's face at x = 0,
// for a partly confined variant.
SetFactory("OpenCASCADE");
DefineConstant[ lc = {2.0, Name "Parameters/element size"} ];
Box(1) = {0, 0, 0, 10, 6, 6};
Box(2) = {-1, -1, -1, 12, 8, 1};
BooleanFragments{ Volume{1, 2}; Delete; }{}
e = 1e-3;
Physical Volume("rock") = {1};
Physical Volume("slab") = {2};
Physical Surface("seat") = Surface In BoundingBox{-e, -e, -e, 10 + e, 6 + e, e};
Physical Surface("west") = Surface In BoundingBox{-e, -e, -e, e, 6 + e, 6 + e};
Physical Surface("ground") = Surface In BoundingBox{-1 - e, -1 - e, -1 - e, 11 + e, 7 + e, -1 + e};
MeshSize{ PointsOf{ Volume{:}; } } = lc;
