// cross2d.geo -- a 2 x 2 square cut by two crossing joints into four
// blocks (OpenCASCADE rectangles fused by BooleanFragments): the crossing
// patch test and the order and rotation checks of tests/junctions.rs.
//
//  y
//  2 +---------+---------+       jx: the joint y = 1 (both halves)
//    |    C    |    D    |       jy: the joint x = 1 (both halves)
//  1 +---jx----+---jx----+       left/right/bottom/top: the sides
//    |    A    jy   B    |       pin (0, 0), roller (2, 0)
//  0 o---------+---------o-- x
//
// quad = 1: transfinite quadrilaterals (n per block side), else triangles
SetFactory("OpenCASCADE");
DefineConstant[ lc = {0.3, Name "Parameters/element size"} ];
DefineConstant[ quad = {0, Name "Parameters/quadrilaterals"} ];
DefineConstant[ n = {3, Name "Parameters/divisions per block side"} ];
Rectangle(1) = {0, 0, 0, 1, 1};
Rectangle(2) = {1, 0, 0, 1, 1};
Rectangle(3) = {0, 1, 0, 1, 1};
Rectangle(4) = {1, 1, 0, 1, 1};
BooleanFragments{ Surface{1:4}; Delete; }{}
Mesh.CharacteristicLengthMax = lc;
If (quad)
  Transfinite Curve{:} = n + 1;
  Transfinite Surface{:};
  Recombine Surface{:};
EndIf
e = 1e-3;
jx() = Curve In BoundingBox{-e, 1 - e, -e, 2 + e, 1 + e, e};
jy() = Curve In BoundingBox{1 - e, -e, -e, 1 + e, 2 + e, e};
left() = Curve In BoundingBox{-e, -e, -e, e, 2 + e, e};
right() = Curve In BoundingBox{2 - e, -e, -e, 2 + e, 2 + e, e};
bottom() = Curve In BoundingBox{-e, -e, -e, 2 + e, e, e};
top() = Curve In BoundingBox{-e, 2 - e, -e, 2 + e, 2 + e, e};
pin() = Point In BoundingBox{-e, -e, -e, e, e, e};
roller() = Point In BoundingBox{2 - e, -e, -e, 2 + e, e, e};
a() = Surface In BoundingBox{-e, -e, -e, 1 + e, 1 + e, e};
b() = Surface In BoundingBox{1 - e, -e, -e, 2 + e, 1 + e, e};
c() = Surface In BoundingBox{-e, 1 - e, -e, 1 + e, 2 + e, e};
d() = Surface In BoundingBox{1 - e, 1 - e, -e, 2 + e, 2 + e, e};
Physical Surface("rock") = {a(), b(), c(), d()};
Physical Surface("a") = {a()};
Physical Surface("b") = {b()};
Physical Surface("c") = {c()};
Physical Surface("d") = {d()};
Physical Curve("jx") = {jx()};
Physical Curve("jy") = {jy()};
Physical Curve("left") = {left()};
Physical Curve("right") = {right()};
Physical Curve("bottom") = {bottom()};
Physical Curve("top") = {top()};
Physical Point("pin") = {pin()};
Physical Point("roller") = {roller()};
