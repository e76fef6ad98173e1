// dam3d.geo -- a slice of a gravity dam between two contraction joints: the
// three blocks of dam.geo (vertical joints at x = 9 and 18 m), D = 10 m
// thick, on a rock foundation. OpenCASCADE volumes (the profile extruded
// over y), joined by BooleanFragments: every shared face is meshed once, so
// the joints and the base are contact groups. The joints end on the base:
// along those lines the two blocks stay joined and pair with the rock.
//
//     z                                  H = 50 m, crest 5 m, base 28 m
//     |  water |\                         rock 150 m x 60 m below z = 0
//     |  ~~~~~ |b1\                      "upstream_face": x = 0 (block 1)
//     |        |  |b2\                   "reservoir_floor": rock top, x < 0
//     |        |  |  |b3\                "sides": y = 0 and y = D (all)
//   ==+========+==+==+===+====== x       "rock_bottom", "rock_ends"
//            base (contact)
//
// Sample run:  subcontact solve geo/dam3d.toml   (make dam3d)
SetFactory("OpenCASCADE");
DefineConstant[ lc = {2.5, Min 0.5, Max 10, Name "Parameters/element size in the dam"} ];
DefineConstant[ lc_rock = {15.0, Min 1, Max 30, Name "Parameters/element size far in the rock"} ];
H = 50; crest = 5; B = 28; j1 = 9; j2 = 18; D = 10;
zd1 = H * (B - j1) / (B - crest);   // downstream face height at the joints
zd2 = H * (B - j2) / (B - crest);

// the profile of each volume as a polygon in y = 0, extruded over y = 0..D
// Prism: in px[], pz[]; out vol
Macro Prism
  np = #px[];
  For i In {0:np-1}
    pts[i] = newp; Point(pts[i]) = {px[i], 0, pz[i]};
  EndFor
  For i In {0:np-1}
    lines[i] = newc; Line(lines[i]) = {pts[i], pts[(i + 1) % np]};
  EndFor
  loop = newll; Curve Loop(loop) = {lines[{0:np-1}]};
  surf = news; Plane Surface(surf) = {loop};
  ext[] = Extrude {0, D, 0} { Surface{surf}; };
  vol = ext[1];
Return

// (gmsh runs a Call at the end of its line: read `vol` on the next one)
px[] = {0, j1, j1, crest, 0};   pz[] = {0, 0, zd1, H, H};    Call Prism;
b1 = vol;
px[] = {j1, j2, j2, j1};        pz[] = {0, 0, zd2, zd1};     Call Prism;
b2 = vol;
px[] = {j2, B, j2};             pz[] = {0, 0, zd2};          Call Prism;
b3 = vol;
px[] = {-60, 90, 90, -60};      pz[] = {-60, -60, 0, 0};     Call Prism;
rk = vol;
out() = BooleanFragments{ Volume{b1, b2, b3, rk}; Delete; }{};

MeshSize{ PointsOf{ Volume{:}; } } = lc_rock;
MeshSize{ PointsOf{ Volume{b1, b2, b3}; } } = lc;

eps = 1e-3;
Physical Volume("block_1") = {b1};
Physical Volume("block_2") = {b2};
Physical Volume("block_3") = {b3};
Physical Volume("rock") = {rk};
Physical Surface("base") = Surface In BoundingBox{-eps, -eps, -eps, B + eps, D + eps, eps};
Physical Surface("joint_12") = Surface In BoundingBox{j1 - eps, -eps, -eps, j1 + eps, D + eps, H};
Physical Surface("joint_23") = Surface In BoundingBox{j2 - eps, -eps, -eps, j2 + eps, D + eps, H};
Physical Surface("upstream_face") = Surface In BoundingBox{-eps, -eps, -eps, eps, D + eps, H + eps};
Physical Surface("reservoir_floor") = Surface In BoundingBox{-60 - eps, -eps, -eps, eps, D + eps, eps};
Physical Surface("rock_bottom") = Surface In BoundingBox{-60 - eps, -eps, -60 - eps, 90 + eps, D + eps, -60 + eps};
Physical Surface("rock_ends") = Surface In BoundingBox{-60 - eps, -eps, -60 - eps, -60 + eps, D + eps, eps};
Physical Surface("rock_ends") += Surface In BoundingBox{90 - eps, -eps, -60 - eps, 90 + eps, D + eps, eps};
Physical Surface("sides") = Surface In BoundingBox{-60 - eps, -eps, -60 - eps, 90 + eps, eps, H + eps};
Physical Surface("sides") += Surface In BoundingBox{-60 - eps, D - eps, -60 - eps, 90 + eps, D + eps, H + eps};
