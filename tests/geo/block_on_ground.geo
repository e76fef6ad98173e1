// block_on_ground.geo -- a block standing on a ground block, for the
// messages about contact groups that miss a body. fragments = 1: the two
// volumes share the nodes of the block's base (BooleanFragments); 0: they
// are meshed apart, each with its own nodes.
//
//            +------+            block: [1, 3] x [1, 3] x [2, 3]
//            | block|
//   +--------+------+--------+   ground: [0, 4] x [0, 4] x [0, 2]
//   |         ground         |
//   +------------------------+   "bottom" (z = 0)
//
// "ground_top": the ground's whole top face (with fragments = 1 the part
// under the block is shared); "block_base": the block's base alone;
// "outer_tops": the block's top and the ground's top beside it (faces of
// two bodies, none shared).
SetFactory("OpenCASCADE");
DefineConstant[ lc = {0.5, Name "Parameters/element size"}, fragments = {1, Name "Parameters/shared nodes"} ];
Box(1) = {0, 0, 0, 4, 4, 2};
Box(2) = {1, 1, 2, 2, 2, 1};
If (fragments == 1)
  BooleanFragments{ Volume{1, 2}; Delete; }{}
EndIf
e = 1e-3;
Physical Volume("ground") = {1};
Physical Volume("block") = {2};
Physical Surface("ground_top") = {Surface In BoundingBox{-e, -e, 2 - e, 4 + e, 4 + e, 2 + e}};
base() = Surface In BoundingBox{1 - e, 1 - e, 2 - e, 3 + e, 3 + e, 2 + e};
Physical Surface("block_base") = {base()};
tops() = Surface In BoundingBox{-e, -e, 2 - e, 4 + e, 4 + e, 3 + e};
tops() -= base();
Physical Surface("outer_tops") = {tops()};
Physical Surface("bottom") = {Surface In BoundingBox{-e, -e, -e, 4 + e, 4 + e, e}};
Mesh.CharacteristicLengthMax = lc;
