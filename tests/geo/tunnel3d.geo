// tunnel3d.geo -- a circular tunnel lining in a block of rock, in 3D: the
// tunnel's axis along y, z up (gravity -z), a slice of length L. The
// lining (r = R - t/2 .. R + t/2) and the rock around it (out to |x|, |z|
// <= D) are OpenCASCADE volumes fragmented so that they share the surface
// r = R + t/2: the contact "interface". full = 1: the whole ring in the
// block [-D, D] x [0, L] x [-D, D]; full = 0: the quarter x, z >= 0 (the
// crown to the springline), cut by the symmetry planes x = 0 and z = 0.
//
//        z
//      D +--------------+  "far" faces: x = +-D, z = +-D
//        |     rock     |
//        |   .-''''-.   |
//        |  /  ____  \  |  lining: R -+ t/2
//        | |  /    \  | |
//        +-|-|------|-|-+-- x      y = 0, L: "ends"
//
// Unstructured tetrahedra, size lc at the lining growing to 4 lc at the
// far boundary.

SetFactory("OpenCASCADE");
DefineConstant[ full = {1, Name "Parameters/whole ring (1) or quarter (0)"} ];
DefineConstant[ R = {5.0, Name "Parameters/lining middle radius"} ];
DefineConstant[ t = {0.4, Name "Parameters/lining thickness"} ];
DefineConstant[ D = {25.0, Name "Parameters/half width of the rock block"} ];
DefineConstant[ L = {2.0, Name "Parameters/slice length along the axis"} ];
DefineConstant[ lc = {0.8, Name "Parameters/element size at the lining"} ];
ri = R - t / 2;
ro = R + t / 2;

x0 = (full == 1) ? -D : 0;
Box(1) = {x0, 0, x0, D - x0, L, D - x0};
Cylinder(2) = {0, 0, 0, 0, L, 0, ro};
Cylinder(3) = {0, 0, 0, 0, L, 0, ri};
// the rock: the block without the opening; the lining: the tube, within the block
rock() = BooleanDifference{ Volume{1}; Delete; }{ Volume{2}; };
tube() = BooleanDifference{ Volume{2}; Delete; }{ Volume{3}; Delete; };
If (full == 0)
  Box(10) = {0, 0, 0, D, L, D};
  tube() = BooleanIntersection{ Volume{tube()}; Delete; }{ Volume{10}; Delete; };
EndIf
all() = BooleanFragments{ Volume{rock(), tube()}; Delete; }{};

// the volumes: the lining is the one within r <= ro
e = 1e-3;
lin() = Volume In BoundingBox{-ro - e, -e, -ro - e, ro + e, L + e, ro + e};
rk() = all();
rk() -= lin();
Physical Volume("lining") = {lin()};
Physical Volume("rock") = {rk()};
// the interface: the lining's faces curved across x and z that span the
// slice (not its ends, its bore r = ri or its symmetry faces)
interface() = {};
For i In {0:#lin()-1}
  s() = Boundary{ Volume{lin(i)}; };
  For j In {0:#s()-1}
    bb() = BoundingBox Surface{s(j)};
    reach = Fabs(bb(0)) > Fabs(bb(3)) ? Fabs(bb(0)) : Fabs(bb(3));
    reach = Fabs(bb(2)) > reach ? Fabs(bb(2)) : reach;
    reach = Fabs(bb(5)) > reach ? Fabs(bb(5)) : reach;
    If (bb(4) - bb(1) > 0.5 * L && bb(3) - bb(0) > e && bb(5) - bb(2) > e && reach > R)
      interface() += {s(j)};
    EndIf
  EndFor
EndFor
Physical Surface("interface") = {interface()};
Physical Surface("ends") = {Surface In BoundingBox{x0 - e, -e, x0 - e, D + e, e, D + e}, Surface In BoundingBox{x0 - e, L - e, x0 - e, D + e, L + e, D + e}};
Physical Surface("far_x") = {Surface In BoundingBox{D - e, -e, x0 - e, D + e, L + e, D + e}, Surface In BoundingBox{x0 - e, -e, x0 - e, x0 + e, L + e, D + e}};
Physical Surface("far_z") = {Surface In BoundingBox{x0 - e, -e, D - e, D + e, L + e, D + e}, Surface In BoundingBox{x0 - e, -e, x0 - e, D + e, L + e, x0 + e}};

Mesh.CharacteristicLengthMin = lc;
Mesh.CharacteristicLengthMax = 4 * lc;
Field[1] = Distance;
Field[1].SurfacesList = {interface()};
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = lc;
Field[2].SizeMax = 4 * lc;
Field[2].DistMin = 0;
Field[2].DistMax = 0.5 * D;
Background Field = 2;
Mesh.CharacteristicLengthExtendFromBoundary = 0;
