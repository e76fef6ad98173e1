// blocks3d.geo -- a block pressed onto a block and pushed along x: the 3D
// partial-slip case (OpenCASCADE boxes joined by BooleanFragments, so the
// shared face is one surface meshed once: the contact "joint").
//
//        z
//        |   +-----------+      "top": z = 2 h (the push and the pressure)
//        |   |   upper   |
//     h  +---+-----------+      "joint": z = h, the shared face
//        |   |   lower   |
//        |   +-----------+--x   "base": z = 0; "x0", "y0", "x1", "y1": the sides
//        0               w      (both blocks), x = 0, y = 0, x = w, y = b
//
// Parameters: lc, the element size; hex = 1 gives transfinite hexahedra
// (w / lc x b / lc x h / lc per block; hex20 with serendipity = 1), hex = 0
// unstructured tetrahedra of size lc (gmsh's default for a CAD volume).
// w, b and h (1 x 1 x 0.5 by default) stretch the blocks: w = b = 1, h = 4 is
// a column on a column (the scaling runs of docs/scaling.md).
SetFactory("OpenCASCADE");
DefineConstant[ lc = {0.125, Name "Parameters/element size"} ];
DefineConstant[ hex = {0, Name "Parameters/hexahedra"} ];
DefineConstant[ serendipity = {0, Name "Parameters/hex20 instead of hex27"} ];
Mesh.SecondOrderIncomplete = serendipity;
DefineConstant[ w = {1.0, Name "Parameters/length along x"} ];
DefineConstant[ b = {1.0, Name "Parameters/width along y"} ];
DefineConstant[ h = {0.5, Name "Parameters/height of each block"} ];
Box(1) = {0, 0, 0, w, b, h};
Box(2) = {0, 0, h, w, b, h};
v() = BooleanFragments{ Volume{1}; Delete; }{ Volume{2}; Delete; };
MeshSize{ PointsOf{ Volume{:}; } } = lc;
eps = 1e-6 * (w + b + h);
If (hex)
  n = Round(w / lc);
  ny = Round(b / lc);
  nz = Round(h / lc);
  // the edges along x, along y, then the vertical ones
  For j In {0:1}
    For k In {0:2}
      Transfinite Curve{ Curve In BoundingBox{-eps, j * b - eps, k * h - eps, w + eps, j * b + eps, k * h + eps} } = n + 1;
    EndFor
  EndFor
  For i In {0:1}
    For k In {0:2}
      Transfinite Curve{ Curve In BoundingBox{i * w - eps, -eps, k * h - eps, i * w + eps, b + eps, k * h + eps} } = ny + 1;
    EndFor
  EndFor
  // the vertical edges: h / lc divisions
  For i In {0:1}
    Transfinite Curve{ Curve In BoundingBox{-eps, -eps, i * h + eps, w + eps, b + eps, (i + 1) * h - eps} } = nz + 1;
  EndFor
  Transfinite Surface{:};
  Recombine Surface{:};
  Transfinite Volume{:};
EndIf
Physical Volume("lower") = {1};
Physical Volume("upper") = {2};
Physical Surface("joint") = Surface In BoundingBox{-eps, -eps, h - eps, w + eps, b + eps, h + eps};
Physical Surface("base") = Surface In BoundingBox{-eps, -eps, -eps, w + eps, b + eps, eps};
Physical Surface("top") = Surface In BoundingBox{-eps, -eps, 2 * h - eps, w + eps, b + eps, 2 * h + eps};
Physical Surface("x0") = Surface In BoundingBox{-eps, -eps, -eps, eps, b + eps, 2 * h + eps};
Physical Surface("y0") = Surface In BoundingBox{-eps, -eps, -eps, w + eps, eps, 2 * h + eps};
Physical Surface("x1") = Surface In BoundingBox{w - eps, -eps, -eps, w + eps, b + eps, 2 * h + eps};
Physical Surface("y1") = Surface In BoundingBox{-eps, b - eps, -eps, w + eps, b + eps, 2 * h + eps};
