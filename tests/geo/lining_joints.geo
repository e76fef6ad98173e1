// lining_joints.geo -- a circular tunnel lining in rock cut by two joints
// that end on it (2D, plane strain, OpenCASCADE): four rock blocks, and
// four T-junctions on the lining-rock interface (issue 35).
//
//   y                          lining: ri = R - t/2 .. ro = R + t/2
//   W +----------------------+         (R = 3, t = 0.3), one body;
//     |      \         /     |   rock: the box |x|, |y| <= W minus the
//     |  B    \       /   A  |         disk r < ro, cut into four blocks
//     |        \ .-. /       |         by the joints, which run from the
//     |         (   )        |         lining out to the box at angles
//     |        / `-' \       |         a, a + 90, a + 180, a + 270
//     |  C    /       \   D  |         (degrees from +x)
//     |      /         \     |
//  -W +----------------------+-- x
//    -W                      W
//
// Groups: "lining", "rock" (surfaces); "interface" (the circle r = ro,
// cut by the joints' ends), "joints", "far" (the box), and "pin", the
// point (ri, 0) of the lining's inner face (curves and a point).
// Sizes: lc on the lining, lc / grade at the joints' ends on it (grade > 1
// grades the interface's facets), lc_far at the box.
//
// Sample run (mesh only):
//   gmsh tests/geo/lining_joints.geo -2 -order 2 -setnumber lc 0.075
SetFactory("OpenCASCADE");
DefineConstant[ lc = {0.15, Min 0.01, Max 1, Name "Parameters/element size at the lining"} ];
DefineConstant[ lc_far = {6, Min 0.5, Max 40, Name "Parameters/element size at the box"} ];
DefineConstant[ W = {60, Min 6, Max 400, Name "Parameters/half width of the box"} ];
DefineConstant[ a = {30, Min -90, Max 90, Name "Parameters/angle of the first joint from x (degrees)"} ];
DefineConstant[ grade = {1, Min 1, Max 10, Name "Parameters/lc over the size at the joints' ends"} ];
R = 3; t = 0.3;
ri = R - t / 2; ro = R + t / 2;

// 1. The rock (the box minus the disk r < ro) and the lining ring.
Rectangle(1) = {-W, -W, 0, 2 * W, 2 * W};
Disk(2) = {0, 0, 0, ro};
Disk(3) = {0, 0, 0, ri};
rock() = BooleanDifference{ Surface{1}; Delete; }{ Surface{2}; };
ring() = BooleanDifference{ Surface{2}; Delete; }{ Surface{3}; Delete; };

// 2. The joints, from the lining out to the box; they cut the rock.
traces() = {};
For k In {0:3}
  th = (a + 90 * k) * Pi / 180;
  c = Cos(th); s = Sin(th);
  L = W / Max(Fabs(c), Fabs(s));
  p1 = newp; Point(p1) = {ro * c, ro * s, 0};
  p2 = newp; Point(p2) = {L * c, L * s, 0};
  l = newc; Line(l) = {p1, p2};
  traces() += l;
EndFor
BooleanFragments{ Surface{rock(), ring()}; Delete; }{ Curve{traces()}; Delete; }

// 3. The groups, sorted by where the curves end.
e = 1e-6 * W;
lining() = Surface In BoundingBox{-ro - e, -ro - e, -e, ro + e, ro + e, e};
blocks() = Surface{:};
blocks() -= lining();
bounds() = Unique(Abs(Boundary{ Surface{:}; }));
interface() = {}; joints() = {}; far() = {};
For i In {0:#bounds() - 1}
  cv = bounds(i);
  ends() = Boundary{ Curve{cv}; };
  xa() = Point{Abs(ends(0))}; xb() = Point{Abs(ends(#ends() - 1))};
  ra = Sqrt(xa(0)^2 + xa(1)^2); rb = Sqrt(xb(0)^2 + xb(1)^2);
  If (Fabs(ra - ro) < e && Fabs(rb - ro) < e)
    interface() += cv;
  ElseIf (Fabs(ra - ri) < e)
    // the inner face: free
  ElseIf (Fabs(ra - ro) < e || Fabs(rb - ro) < e)
    joints() += cv;
  Else
    far() += cv;
  EndIf
EndFor
pin() = Point In BoundingBox{ri - e, -e, -e, ri + e, e, e};

Physical Surface("lining") = {lining()};
Physical Surface("rock") = {blocks()};
Physical Curve("interface") = {interface()};
Physical Curve("joints") = {joints()};
Physical Curve("far") = {far()};
Physical Point("pin") = {pin()};

// 4. Sizes.
MeshSize{ PointsOf{ Surface{:}; } } = lc_far;
MeshSize{ PointsOf{ Surface{lining()}; } } = lc;
MeshSize{ PointsOf{ Curve{joints()}; } } = lc;
MeshSize{ PointsOf{ Curve{far()}; } } = lc_far;
MeshSize{ PointsOf{ Curve{interface()}; } } = lc;
For i In {0:#joints() - 1}
  ends() = Boundary{ Curve{joints(i)}; };
  For j In {0:#ends() - 1}
    xp() = Point{Abs(ends(j))};
    If (Fabs(Sqrt(xp(0)^2 + xp(1)^2) - ro) < e)
      MeshSize{ Abs(ends(j)) } = lc / grade;
    EndIf
  EndFor
EndFor
