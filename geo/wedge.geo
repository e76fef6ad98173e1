// wedge.geo -- a rock wedge in a V-groove (Hoek & Bray, Rock Slope
// Engineering): a prism of rock resting on two joint planes that dip
// towards each other, free at its top and at its ends, sliding along the
// line where the joints meet. The model is drawn in the groove's own frame
// (OpenCASCADE): y along the line of intersection, z along the bisector of
// the V, so that every face is found by a bounding box. The line of
// intersection plunges at psi in the field: wedge.toml turns the gravity
// vector instead of the model (g (0, -sin psi, -cos psi)).
//
// Sample runs:
//   subcontact solve geo/wedge.toml      the load step and the safety search ([safety])
//   make safety                          with the rigid-block factor beside it
//   setnumber = { lc = 0.5 } in wedge.toml    a finer mesh
//
//   cross-section (x, z), y into the page:     along the groove (y, z):
//
//        -b     0     b                          top (free)
//   z = d +-----+-----+  top (free)          +----------------------+
//         |\   wedge  /|                     |        wedge         | ends free
//         | \        / |  "groove": both     +======================+ (y = 0, L)
//         |  \  xi  /  |  joint planes,      |                      |
//         |   \    /   |  one contact        |         rock         | "rock_ends"
//  z = h0 +    \__/    +  group              |                      | held along y
//   z = 0 |     \/     |  crevice (open)     +----------------------+
//         |    rock    | "rock_sides"              "rock_base" (held)
//  z = -d +------------+ held along x
//        -2b          2b
//
// xi is the wedge's included angle between the joint planes (90 degrees
// by default, each plane dipping 45 degrees towards the other in the
// section); b = d tan(xi / 2). The wedge stops h0 above the line where the
// planes meet, leaving a crevice along it: the joints are two planes that
// do not touch each other, as the rigid-block analysis assumes (on a sharp
// crease the two faces' pairs share their nodes, which ties them together).

SetFactory("OpenCASCADE");
DefineConstant[ lc = {1.0, Min 0.1, Max 4, Name "Parameters/element size"} ];
DefineConstant[ xi = {90, Min 20, Max 160, Name "Parameters/included angle of the V (degrees)"} ];
DefineConstant[ d = {4.0, Name "Parameters/depth of the V"} ];
DefineConstant[ h0 = {0.25, Name "Parameters/height of the crevice at the bottom of the V"} ];
DefineConstant[ L = {12.0, Name "Parameters/length of the wedge along the groove"} ];
b = d * Tan(xi * Pi / 360);
c = b * h0 / d;   // half width of the crevice's top

// 1. The groove (a triangle in the section y = 0) and the wedge that fills
// it above the crevice (a trapezoid), both extruded along the groove.
Point(1) = {-b, 0, d, lc};
Point(2) = {0, 0, 0, lc};
Point(3) = {b, 0, d, lc};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 1};
Curve Loop(1) = {1, 2, 3};
Plane Surface(1) = {1};
v[] = Extrude {0, L, 0} { Surface{1}; };
// (h0 = 0: no crevice, the wedge is the groove itself, on a sharp crease)
If (h0 > 0)
  Point(11) = {-c, 0, h0, lc};
  Point(12) = {c, 0, h0, lc};
  Line(11) = {1, 11};
  Line(12) = {11, 12};
  Line(13) = {12, 3};
  Curve Loop(11) = {11, 12, 13, 3};
  Plane Surface(11) = {11};
  w[] = Extrude {0, L, 0} { Surface{11}; };
EndIf

// 2. The rock: a box with the groove cut out, fragmented with the wedge so
// that the joint planes are surfaces shared by both.
Box(10) = {-2 * b, 0, -d, 4 * b, L, 2 * d};
If (h0 > 0)
  r() = BooleanDifference{ Volume{10}; Delete; }{ Volume{v[1]}; Delete; };
Else
  r() = BooleanDifference{ Volume{10}; Delete; }{ Volume{v[1]}; };
  w[] = v[];
EndIf
all() = BooleanFragments{ Volume{r(), w[1]}; Delete; }{};

// 3. Groups, found by bounding boxes (e: OpenCASCADE's boxes are enlarged).
e = 1e-3;
wedge() = Volume In BoundingBox{-b - e, -e, h0 - e, b + e, L + e, d + e};
rock() = all();
rock() -= wedge();
wall() = Abs(Boundary{ Volume{wedge()}; });
Physical Volume("rock") = {rock()};
Physical Volume("wedge") = {wedge()};
Physical Surface("groove") = {Surface In BoundingBox{-b - e, -e, h0 - e, -c + e, L + e, d + e}, Surface In BoundingBox{c - e, -e, h0 - e, b + e, L + e, d + e}};
Physical Surface("rock_base") = {Surface In BoundingBox{-2 * b - e, -e, -d - e, 2 * b + e, L + e, -d + e}};
Physical Surface("rock_sides") = {Surface In BoundingBox{-2 * b - e, -e, -d - e, -2 * b + e, L + e, d + e}, Surface In BoundingBox{2 * b - e, -e, -d - e, 2 * b + e, L + e, d + e}};
ends() = Surface In BoundingBox{-2 * b - e, -e, -d - e, 2 * b + e, e, d + e};
ends() += Surface In BoundingBox{-2 * b - e, L - e, -d - e, 2 * b + e, L + e, d + e};
ends() -= wall();
Physical Surface("rock_ends") = {ends()};
Physical Surface("top") = {Surface In BoundingBox{-b - e, -e, d - e, b + e, L + e, d + e}};
Mesh.CharacteristicLengthMax = lc;
