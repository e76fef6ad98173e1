// cross3d.geo -- a 2 x 2 x 2 cube cut by three orthogonal joints into
// eight blocks (OpenCASCADE boxes fused by BooleanFragments): four blocks
// meet along each half-axis of the crossings and eight at the centre. The
// crossing patch test and the order and rotation checks of
// tests/junctions.rs.
//
//            z                        jx, jy, jz: the joints x = 1, y = 1,
//            |   +-------+-------+    z = 1 (four faces each)
//            |  /   b6  /  b7   /|    x0, x1, y0, y1, z0, z1: the sides
//            | +-------+-------+ |    A (0, 0, 0), B (2, 0, 0), C (0, 2, 0)
//            |/   b4  /   b5  /| +
//            +-------+-------+ |/|    blocks b0..b7: bit 0 x > 1,
//            |       |       | + |    bit 1 y > 1, bit 2 z > 1
//            |  b0   |  b1   |/| +
//          A o-------+-------o B/ -- x
//
// hex = 1: transfinite hexahedra (n per block edge), serendipity = 1 with
// `-order 2` gives hex20; else tetrahedra of size lc.
SetFactory("OpenCASCADE");
DefineConstant[ lc = {0.5, Name "Parameters/element size"} ];
DefineConstant[ hex = {0, Name "Parameters/hexahedra"} ];
DefineConstant[ n = {2, Name "Parameters/divisions per block edge"} ];
DefineConstant[ serendipity = {0, Name "Parameters/hex20 instead of hex27"} ];
Mesh.SecondOrderIncomplete = serendipity;
For i In {0:7}
  Box(i + 1) = {i % 2, Floor(i / 2) % 2, Floor(i / 4), 1, 1, 1};
EndFor
BooleanFragments{ Volume{1:8}; Delete; }{}
Mesh.CharacteristicLengthMax = lc;
If (hex)
  Transfinite Curve{:} = n + 1;
  Transfinite Surface{:};
  Recombine Surface{:};
  Transfinite Volume{:};
EndIf
e = 1e-3;
For i In {0:7}
  x = i % 2; y = Floor(i / 2) % 2; z = Floor(i / 4);
  v() = Volume In BoundingBox{x - e, y - e, z - e, x + 1 + e, y + 1 + e, z + 1 + e};
  Physical Volume(Sprintf("b%g", i)) = {v()};
  all(i) = v(0);
EndFor
Physical Volume("rock") = {all()};
Physical Surface("jx") = Surface In BoundingBox{1 - e, -e, -e, 1 + e, 2 + e, 2 + e};
Physical Surface("jy") = Surface In BoundingBox{-e, 1 - e, -e, 2 + e, 1 + e, 2 + e};
Physical Surface("jz") = Surface In BoundingBox{-e, -e, 1 - e, 2 + e, 2 + e, 1 + e};
Physical Surface("x0") = Surface In BoundingBox{-e, -e, -e, e, 2 + e, 2 + e};
Physical Surface("x1") = Surface In BoundingBox{2 - e, -e, -e, 2 + e, 2 + e, 2 + e};
Physical Surface("y0") = Surface In BoundingBox{-e, -e, -e, 2 + e, e, 2 + e};
Physical Surface("y1") = Surface In BoundingBox{-e, 2 - e, -e, 2 + e, 2 + e, 2 + e};
Physical Surface("z0") = Surface In BoundingBox{-e, -e, -e, 2 + e, 2 + e, e};
Physical Surface("z1") = Surface In BoundingBox{-e, -e, 2 - e, 2 + e, 2 + e, 2 + e};
Physical Point("A") = Point In BoundingBox{-e, -e, -e, e, e, e};
Physical Point("B") = Point In BoundingBox{2 - e, -e, -e, 2 + e, e, e};
Physical Point("C") = Point In BoundingBox{-e, 2 - e, -e, e, 2 + e, e};
