// contact_pyramids.geo -- two blocks in contact across a face of pyramids,
// for the contact patch test of pyramids (tests/contact3d.rs): the upper
// block structured hexahedra, the lower one unstructured tetrahedra, so
// that gmsh fills the lower side of the joint's quadrangles with pyramids
// (pyramid5; pyramid14 at order 2, pyramid13 with serendipity = 1).
//
//        z   +------------+   "top"  z = 2h      upper: hexahedra
//        |   |   upper    |
//        h   +============+   "joint"            the lower block's cells on
//            |   lower    |                      the joint: pyramids
//        0   +------------+-- x   "base" z = 0   lower: tetrahedra
//
// The faces x = 0, w and y = 0, b are "x0", "x1", "y0", "y1", as in
// geo/blocks3d.geo.

SetFactory("OpenCASCADE");
DefineConstant[ n = {3, Name "Parameters/hexahedra along each edge of the upper block"} ];
DefineConstant[ lc = {0.3, Name "Parameters/tetrahedron size"} ];
DefineConstant[ serendipity = {0, Name "Parameters/pyramid13 instead of pyramid14"} ];
Mesh.SecondOrderIncomplete = serendipity;
w = 1.0; b = 1.0; h = 0.5;
Box(1) = {0, 0, 0, w, b, h};
Box(2) = {0, 0, h, w, b, h};
BooleanFragments{ Volume{1, 2}; Delete; }{}
eps = 1e-3;
up() = Volume In BoundingBox{-eps, -eps, h - eps, w + eps, b + eps, 2 * h + eps};
Transfinite Curve{ Curve In BoundingBox{-eps, -eps, h - eps, w + eps, b + eps, 2 * h + eps} } = n + 1;
Transfinite Surface{ Surface In BoundingBox{-eps, -eps, h - eps, w + eps, b + eps, 2 * h + eps} };
Recombine Surface{ Surface In BoundingBox{-eps, -eps, h - eps, w + eps, b + eps, 2 * h + eps} };
Transfinite Volume{up()};
Physical Volume("lower") = Volume In BoundingBox{-eps, -eps, -eps, w + eps, b + eps, h + eps};
Physical Volume("upper") = {up()};
Physical Surface("joint") = Surface In BoundingBox{-eps, -eps, h - eps, w + eps, b + eps, h + eps};
Physical Surface("base") = Surface In BoundingBox{-eps, -eps, -eps, w + eps, b + eps, eps};
Physical Surface("top") = Surface In BoundingBox{-eps, -eps, 2 * h - eps, w + eps, b + eps, 2 * h + eps};
Physical Surface("x0") = Surface In BoundingBox{-eps, -eps, -eps, eps, b + eps, 2 * h + eps};
Physical Surface("y0") = Surface In BoundingBox{-eps, -eps, -eps, w + eps, eps, 2 * h + eps};
Physical Surface("x1") = Surface In BoundingBox{w - eps, -eps, -eps, w + eps, b + eps, 2 * h + eps};
Physical Surface("y1") = Surface In BoundingBox{-eps, b - eps, -eps, w + eps, b + eps, 2 * h + eps};
Mesh.CharacteristicLengthMax = lc;
