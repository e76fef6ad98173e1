// rockmass.geo -- a cube of rock cut by three orthogonal joint sets into
// n x n x n blocks, as a rock engineer builds it in OpenCASCADE: one box,
// fragmented by the joint planes (BooleanFragments), one physical volume for
// the whole mass and one physical surface per joint set.
//
//          z
//          |  +---+---+---+---+      jx: the planes x = i L/n, i = 1..n-1
//          | /   /   /   /   /|      jy: y = i L/n,  jz: z = i L/n
//          |+---+---+---+---+ |      (n - 1 planes per set; blocks meet four
//          ||   |   |   |   | +      along a line and eight at a point)
//          |+---+---+---+---+/|
//          ||   |   |   |   | +      base (z = 0), top (z = L),
//          |+---+---+---+---+/       x0, x1, y0, y1: the sides
//          o------------------ x
//
// hex = 1: transfinite hexahedra, m per block edge (with `-order 2`
// serendipity = 1 gives hex20); hex = 0: tetrahedra of size L/(n m).
SetFactory("OpenCASCADE");
DefineConstant[ L = {10.0, Name "Parameters/edge of the cube"} ];
DefineConstant[ n = {4, Name "Parameters/blocks per edge"} ];
DefineConstant[ m = {2, Name "Parameters/elements per block edge"} ];
DefineConstant[ hex = {1, Name "Parameters/hexahedra"} ];
DefineConstant[ serendipity = {1, Name "Parameters/hex20 instead of hex27"} ];
Mesh.SecondOrderIncomplete = serendipity;
a = L / n;
Box(1) = {0, 0, 0, L, L, L};
// the joint planes, each a rectangle a little larger than the cube
p = 0;
For i In {1:n - 1}
  p += 1; Rectangle(100 + p) = {i * a, -1, -1, L + 2, L + 2}; Rotate{{0, 1, 0}, {i * a, -1, -1}, -Pi / 2}{ Surface{100 + p}; }
  p += 1; Rectangle(100 + p) = {-1, i * a, -1, L + 2, L + 2}; Rotate{{1, 0, 0}, {-1, i * a, -1}, Pi / 2}{ Surface{100 + p}; }
  p += 1; Rectangle(100 + p) = {-1, -1, i * a, L + 2, L + 2};
EndFor
If (n > 1)
  BooleanFragments{ Volume{1}; Delete; }{ Surface{101:100 + p}; Delete; }
  // what the planes left outside the cube
  Recursive Delete{ Surface{:}; }
EndIf
Mesh.CharacteristicLengthMax = a / m;
If (hex)
  Transfinite Curve{:} = m + 1;
  Transfinite Surface{:};
  Recombine Surface{:};
  Transfinite Volume{:};
EndIf
e = 1e-3;
Physical Volume("rock") = Volume{:};
jx() = {}; jy() = {}; jz() = {};
For i In {1:n - 1}
  jx() += Surface In BoundingBox{i * a - e, -e, -e, i * a + e, L + e, L + e};
  jy() += Surface In BoundingBox{-e, i * a - e, -e, L + e, i * a + e, L + e};
  jz() += Surface In BoundingBox{-e, -e, i * a - e, L + e, L + e, i * a + e};
EndFor
Physical Surface("jx") = {jx()};
Physical Surface("jy") = {jy()};
Physical Surface("jz") = {jz()};
Physical Surface("base") = Surface In BoundingBox{-e, -e, -e, L + e, L + e, e};
Physical Surface("top") = Surface In BoundingBox{-e, -e, L - e, L + e, L + e, L + e};
Physical Surface("x0") = Surface In BoundingBox{-e, -e, -e, e, L + e, L + e};
Physical Surface("x1") = Surface In BoundingBox{L - e, -e, -e, L + e, L + e, L + e};
Physical Surface("y0") = Surface In BoundingBox{-e, -e, -e, L + e, e, L + e};
Physical Surface("y1") = Surface In BoundingBox{-e, L - e, -e, L + e, L + e, L + e};
