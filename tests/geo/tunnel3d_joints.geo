// tunnel3d_joints.geo -- a circular tunnel through rock cut by three
// oblique joint sets, written by hand the way a rock engineer would before
// `[[joint_sets]]` (issue 28's convergence corpus). OpenCASCADE: a box of
// rock minus the opening, cut by the joint planes (BooleanFragments); the
// faces are sorted into groups afterwards by their corner points, because
// the .geo language cannot tell which plane a fragment came from.
//
//   z up, x east, y north (the tunnel's axis)
//
//        z = H/2 +------------------+   "top"    z = +H/2
//                |   J1 60/030 /    |   "bottom" z = -H/2
//                |  /  .----. /  /  |   "sides"  x = +-W/2
//                | /  ( R=3  )  /   |   "ends"   y = 0, L
//                |/    `----'  /    |   "wall"   the opening, r = R
//       z = -H/2 +------------------+   J1, J2, J3: one group per set
//              x = -W/2          x = W/2
//
// A set is given as in the rock engineer's notation: dip / dip direction
// (degrees; dip direction clockwise from north), spacing and offset, the
// upward normal n = (sin dip sin dd, sin dip cos dd, cos dip), plane k of
// the set n . x = off + k sp. Each plane starts as a large square in z = 0,
// is turned by its dip about its strike (-cos dd, sin dd, 0), moved along
// n, and clipped to the box.
SetFactory("OpenCASCADE");
DefineConstant[ lc = {1.0, Min 0.2, Max 5, Name "Parameters/element size at the opening"} ];
DefineConstant[ lc_far = {2.5, Min 0.5, Max 10, Name "Parameters/element size at the box"} ];
DefineConstant[ W = {24, Name "Parameters/box width (x)"} ];
DefineConstant[ L = {12, Name "Parameters/box length along the tunnel (y)"} ];
DefineConstant[ H = {24, Name "Parameters/box height (z)"} ];
DefineConstant[ R = {3, Name "Parameters/radius of the opening"} ];
DefineConstant[ sets = {3, Name "Parameters/how many of the three sets"} ];
dip[] = {60, 70, 10};
dd[] = {30, 150, 270};
sp[] = {5, 5, 4};
off[] = {1.3, 0.7, 0.0};

// 1. The rock: the box minus the opening.
Box(1) = {-W / 2, 0, -H / 2, W, L, H};
Box(2) = {-W / 2, 0, -H / 2, W, L, H};   // a copy to clip the planes with
Cylinder(3) = {0, -1, 0, 0, L + 2, 0, R};
rock() = BooleanDifference{ Volume{1}; Delete; }{ Volume{3}; Delete; };

// 2. The joint planes, clipped to the box.
big = 2 * (W + L + H);
planes() = {};
For j In {0:sets - 1}
  a = dip[j] * Pi / 180; d = dd[j] * Pi / 180;
  nx = Sin(a) * Sin(d); ny = Sin(a) * Cos(d); nz = Cos(a);
  reach = (Fabs(nx) * W + Fabs(ny) * L + Fabs(nz) * H) / 2;
  cy = nx * 0 + ny * L / 2;   // n . (centre of the box)
  For k In {Ceil((cy - reach - off[j]) / sp[j]) : Floor((cy + reach - off[j]) / sp[j])}
    c = off[j] + k * sp[j];
    s = news; Rectangle(s) = {-big / 2, -big / 2, 0, big, big};
    Rotate { {-Cos(d), Sin(d), 0}, {0, 0, 0}, a } { Surface{s}; }
    Translate { c * nx, c * ny, c * nz } { Surface{s}; }
    clipped() = BooleanIntersection{ Surface{s}; Delete; }{ Volume{2}; };
    planes() += clipped();
  EndFor
EndFor
Recursive Delete { Volume{2}; }

// 3. The planes cut the rock into blocks; pieces inside the opening bound
// no block and are deleted.
all() = BooleanFragments{ Volume{rock()}; Delete; }{ Surface{planes()}; Delete; };
bounds() = Unique(Abs(Boundary{ Volume{:}; }));
loose() = Surface{:};
loose() -= bounds();
If (#loose() > 0)
  Recursive Delete { Surface{loose()}; }
EndIf

// 4. Every face of a block, sorted by its corner points.
e = 1e-4 * (W + H);
J1() = {}; J2() = {}; J3() = {};
wall() = {}; top() = {}; bottom() = {}; sides() = {}; ends() = {};
For i In {0:#bounds() - 1}
  f = bounds(i);
  pts() = PointsOf{ Surface{f}; };
  // the largest departure of the corners from each candidate
  dwall = 0; dtop = 0; dbot = 0; dxs = 0; dys = 0;
  x0() = Point{pts(0)};
  For q In {0:#pts() - 1}
    x() = Point{pts(q)};
    dwall = Max(dwall, Fabs(Sqrt(x(0)^2 + x(2)^2) - R));
    dtop = Max(dtop, Fabs(x(2) - H / 2));
    dbot = Max(dbot, Fabs(x(2) + H / 2));
    dxs = Max(dxs, Fabs(x(0) - x0(0)) + Fabs(Fabs(x(0)) - W / 2));
    dys = Max(dys, Fabs(x(1) - x0(1)) + Min(Fabs(x(1)), Fabs(x(1) - L)));
  EndFor
  set = -1;
  For j In {0:sets - 1}
    a = dip[j] * Pi / 180; d = dd[j] * Pi / 180;
    nx = Sin(a) * Sin(d); ny = Sin(a) * Cos(d); nz = Cos(a);
    c0 = nx * x0(0) + ny * x0(1) + nz * x0(2);
    k = Round((c0 - off[j]) / sp[j]);
    dev = 0;
    For q In {0:#pts() - 1}
      x() = Point{pts(q)};
      dev = Max(dev, Fabs(nx * x(0) + ny * x(1) + nz * x(2) - off[j] - k * sp[j]));
    EndFor
    If (dev < e)
      set = j;
    EndIf
  EndFor
  If (dtop < e)
    top() += f;
  ElseIf (dbot < e)
    bottom() += f;
  ElseIf (dxs < e)
    sides() += f;
  ElseIf (dys < e)
    ends() += f;
  ElseIf (dwall < e)
    wall() += f;
  ElseIf (set == 0)
    J1() += f;
  ElseIf (set == 1)
    J2() += f;
  ElseIf (set == 2)
    J3() += f;
  Else
    Error("tunnel3d_joints.geo: face %g is neither a joint nor a side", f);
  EndIf
EndFor

Physical Volume("rock") = Volume{:};
Physical Surface("J1") = {J1()};
If (sets > 1)
  Physical Surface("J2") = {J2()};
EndIf
If (sets > 2)
  Physical Surface("J3") = {J3()};
EndIf
Physical Surface("wall") = {wall()};
Physical Surface("top") = {top()};
Physical Surface("bottom") = {bottom()};
Physical Surface("sides") = {sides()};
Physical Surface("ends") = {ends()};
vols() = Volume{:};
Printf("tunnel3d_joints.geo: %g blocks, %g / %g / %g joint faces", #vols(), #J1(), #J2(), #J3());

// 5. Element size: lc at the opening growing to lc_far at the box.
Mesh.CharacteristicLengthMin = lc;
Mesh.CharacteristicLengthMax = lc_far;
Field[1] = Distance;
Field[1].SurfacesList = {wall()};
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = lc;
Field[2].SizeMax = lc_far;
Field[2].DistMin = 0;
Field[2].DistMax = W / 2;
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;

Mesh.HighOrderOptimize = 2;   // quadratic elements on the curved opening stay valid
