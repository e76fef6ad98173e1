// joint_sets_by_hand.geo -- the rock mass of tests/joint_sets.rs built by
// hand, as a user had to before [[joint_sets]]: a 20 m cube minus a tunnel
// of radius 3, each joint plane made from its dip and dip direction, the
// rock fragmented by them, and every face sorted into a group by testing
// its corner points against the box, the tunnel and the planes (all on
// one plane k of a set; OpenCASCADE cannot say which plane a piece came
// from). Sets: 60/030, 70/150, 10/270, 5, 5 and 4 m apart.
SetFactory("OpenCASCADE");
DefineConstant[ lc = {2.0, Name "Parameters/element size"} ];
Box(1) = {-10, 0, -10, 20, 20, 20};
Cylinder(2) = {0, -1, 0, 0, 22, 0, 3};
BooleanDifference{ Volume{1}; Delete; }{ Volume{2}; Delete; }
dip[] = {60, 70, 10}; dd[] = {30, 150, 270}; sp[] = {5, 5, 4}; off[] = {1.3, 0, 0.5};
cxs[] = {-10, 10}; cys[] = {0, 20};
planes() = {};
For j In {0:2}
  d = dip[j] * Pi / 180; a = dd[j] * Pi / 180;
  nx[j] = Sin(d) * Sin(a); ny[j] = Sin(d) * Cos(a); nz[j] = Cos(d);
  lo = 1e9; hi = -1e9;
  For i In {0:7}
    v = nx[j] * cxs[i % 2] + ny[j] * cys[Floor(i / 2) % 2] + nz[j] * cxs[Floor(i / 4)];
    lo = Min(lo, v); hi = Max(hi, v);
  EndFor
  For k In {Ceil((lo - off[j]) / sp[j]) : Floor((hi - off[j]) / sp[j])}
    s = news; Rectangle(s) = {-40, -40, 0, 80, 80};
    Rotate{{Cos(a), -Sin(a), 0}, {0, 0, 0}, -d}{ Surface{s}; }
    c = off[j] + k * sp[j];
    Translate{c * nx[j], c * ny[j], c * nz[j]}{ Surface{s}; }
    planes() += s;
  EndFor
EndFor
BooleanFragments{ Volume{1}; Delete; }{ Surface{planes()}; Delete; }
faces() = Unique(Abs(Boundary{ Volume{:}; }));
all() = Surface{:};
outside() = {};
For i In {0:#all() - 1}
  used = 0;
  For q In {0:#faces() - 1}
    If (faces(q) == all(i)) used = 1; EndIf
  EndFor
  If (!used) outside() += all(i); EndIf
EndFor
Recursive Delete{ Surface{outside()}; }
e = 1e-6;
J1() = {}; J2() = {}; J3() = {}; wall() = {}; top() = {}; base() = {}; sides() = {}; ends() = {};
For i In {0:#faces() - 1}
  f = faces(i);
  pts() = PointsOf{ Surface{f}; };
  onwall = 1; ontop = 1; onbase = 1; onside = 1; onend = 1; onset[] = {1, 1, 1}; k0[] = {0, 0, 0};
  For q In {0:#pts() - 1}
    x() = Point{pts(q)};
    If (Fabs(Sqrt(x(0)^2 + x(2)^2) - 3) > e) onwall = 0; EndIf
    If (Fabs(x(2) - 10) > e) ontop = 0; EndIf
    If (Fabs(x(2) + 10) > e) onbase = 0; EndIf
    If (Fabs(Fabs(x(0)) - 10) > e) onside = 0; EndIf
    If (Fabs(x(1) - 10) < 10 - e) onend = 0; EndIf
    For j In {0:2}
      t = (nx[j] * x(0) + ny[j] * x(1) + nz[j] * x(2) - off[j]) / sp[j];
      If (q == 0) k0[j] = Round(t); EndIf
      If (Fabs(t - k0[j]) > e) onset[j] = 0; EndIf
    EndFor
  EndFor
  If (onwall) wall() += f;
  ElseIf (ontop) top() += f;
  ElseIf (onbase) base() += f;
  ElseIf (onside) sides() += f;
  ElseIf (onend) ends() += f;
  ElseIf (onset[0]) J1() += f;
  ElseIf (onset[1]) J2() += f;
  ElseIf (onset[2]) J3() += f;
  Else Error("face %g is in no group", f);
  EndIf
EndFor
Physical Volume("rock") = Volume{:};
Physical Surface("J1") = {J1()};
Physical Surface("J2") = {J2()};
Physical Surface("J3") = {J3()};
Physical Surface("wall") = {wall()};
Physical Surface("top") = {top()};
Physical Surface("base") = {base()};
Physical Surface("sides") = {sides()};
Physical Surface("ends") = {ends()};
MeshSize{ PointsOf{ Volume{:}; } } = lc;
