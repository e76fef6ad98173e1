// tunnel_joints.geo -- a circular tunnel in rock cut by three joint sets
// (2D, plane strain). OpenCASCADE: a 30 m x 30 m box minus the opening
// (BooleanDifference), then cut by the joint traces (BooleanFragments): the
// rock falls apart into about 150 blocks, one body group "rock", and each
// joint set is one contact group.
//
//   y                                      sets (angle from x, spacing,
//   15 +-------------------------------+     offset of a trace from the
//      |  /    /  `-.  /    /    /     |     centre, measured along the
//      |-/----/------`/-.--/----/------|     set's normal):
//      |/    /       /   `-.   /       |   bedding    0 deg, 3 m, 1.5 m
//      /    /    .--/--.   /`-.        |   joints_a  60 deg, 4 m, 3.5 m
//      |---/----/--/----\-/-----`-.----|   joints_b 150 deg, 6 m, 2.5 m
//      |  /    | (  R = 3 m )  /    /  |
//      | /     /  `------'   /    /    |   "wall": the opening r = R
//    0 |/-----/------/------/----/-----|   "top": y = 15, "bottom": y = -15,
//      |    ...                        |   "sides": x = -15 and x = 15
//  -15 +-------------------------------+-- x
//    -15               0               15
//
// The traces are clipped to the box analytically, so they end on its
// sides; traces that would cut off less than 5 % of it are left out. The
// curves are sorted into the groups by their end points: both on the circle
// (the wall), on a side of the box, or along a set's angle.
//
// Sample run:  subcontact solve geo/tunnel_joints.toml   (make tunnel-joints)
SetFactory("OpenCASCADE");
DefineConstant[ lc = {0.6, Min 0.1, Max 3, Name "Parameters/element size at the opening"} ];
DefineConstant[ lc_far = {2.0, Min 0.5, Max 6, Name "Parameters/element size at the box"} ];
DefineConstant[ W = {15, Min 6, Max 60, Name "Parameters/half width of the box"} ];
R = 3;     // radius of the opening
ang[] = {0, 60, 150};   // bedding, joints_a, joints_b
sp[] = {3, 4, 6};
off[] = {1.5, 3.5, 2.5};

// 1. The rock: the box minus the opening.
Rectangle(1) = {-W, -W, 0, 2 * W, 2 * W};
Disk(2) = {0, 0, 0, R};
rock() = BooleanDifference{ Surface{1}; Delete; }{ Surface{2}; Delete; };

// 2. The joint traces of every set, c = off + k sp along the normal
// (-sin a, cos a), clipped to the box: x = c n + t d, t0 <= t <= t1.
traces() = {};
For j In {0:#ang[] - 1}
  ca = Cos(ang[j] * Pi / 180); sa = Sin(ang[j] * Pi / 180);
  cmax = W * (Fabs(ca) + Fabs(sa));
  For k In {Ceil((-cmax - off[j]) / sp[j]) : Floor((cmax - off[j]) / sp[j])}
    c = off[j] + k * sp[j];
    px = -c * sa; py = c * ca;
    t0 = -1e9; t1 = 1e9;
    If (Fabs(ca) > 1e-9)
      ta = (-W - px) / ca; tb = (W - px) / ca;
      t0 = Max(t0, Min(ta, tb)); t1 = Min(t1, Max(ta, tb));
    EndIf
    If (Fabs(sa) > 1e-9)
      ta = (-W - py) / sa; tb = (W - py) / sa;
      t0 = Max(t0, Min(ta, tb)); t1 = Min(t1, Max(ta, tb));
    EndIf
    If (t1 - t0 > 0.05 * W)
      p1 = newp; Point(p1) = {px + t0 * ca, py + t0 * sa, 0};
      p2 = newp; Point(p2) = {px + t1 * ca, py + t1 * sa, 0};
      l = newc; Line(l) = {p1, p2};
      traces() += l;
    EndIf
  EndFor
EndFor

// 3. The traces cut the rock into blocks (their parts inside the opening
// bound no block: they are left out of every group below).
BooleanFragments{ Surface{rock()}; Delete; }{ Curve{traces()}; Delete; }

// 4. Every curve that bounds a block, sorted by its end points.
e = 1e-6 * W;
bounds() = Unique(Abs(Boundary{ Surface{:}; }));
bedding() = {}; joints_a() = {}; joints_b() = {};
wall() = {}; top() = {}; bottom() = {}; sides() = {};
For i In {0:#bounds() - 1}
  cv = bounds(i);
  ends() = Boundary{ Curve{cv}; };
  If (#ends() < 2)
    wall() += cv;
  Else
    xa() = Point{Abs(ends(0))}; xb() = Point{Abs(ends(1))};
    dx = xb(0) - xa(0); dy = xb(1) - xa(1);
    ra = Sqrt(xa(0)^2 + xa(1)^2); rb = Sqrt(xb(0)^2 + xb(1)^2);
    If (Fabs(ra - R) < e && Fabs(rb - R) < e)
      wall() += cv;
    ElseIf (Fabs(dy) < e && Fabs(xa(1) - W) < e)
      top() += cv;
    ElseIf (Fabs(dy) < e && Fabs(xa(1) + W) < e)
      bottom() += cv;
    ElseIf (Fabs(dx) < e && Fabs(Fabs(xa(0)) - W) < e)
      sides() += cv;
    Else
      a = Atan2(dy, dx) * 180 / Pi;
      If (a < -1e-6)
        a += 180;
      EndIf
      If (Fabs(a - ang[0]) < 1e-3 || Fabs(a - ang[0] - 180) < 1e-3)
        bedding() += cv;
      ElseIf (Fabs(a - ang[1]) < 1e-3)
        joints_a() += cv;
      ElseIf (Fabs(a - ang[2]) < 1e-3)
        joints_b() += cv;
      Else
        Error("tunnel_joints.geo: curve %g (angle %g) is neither a trace nor a side", cv, a);
      EndIf
    EndIf
  EndIf
EndFor

Physical Surface("rock") = Surface{:};
Physical Curve("bedding") = {bedding()};
Physical Curve("joints_a") = {joints_a()};
Physical Curve("joints_b") = {joints_b()};
Physical Curve("wall") = {wall()};
Physical Curve("top") = {top()};
Physical Curve("bottom") = {bottom()};
Physical Curve("sides") = {sides()};

// 5. Sizes: lc_far everywhere, lc on the opening.
MeshSize{ PointsOf{ Surface{:}; } } = lc_far;
MeshSize{ PointsOf{ Curve{wall()}; } } = lc;
