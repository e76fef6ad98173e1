// beam3d.geo -- a beam of span L (x), width b (y) and depth h (z) on three
// point supports, a point on its top at (a, b/2, h) (tests/point_loads.rs,
// tests/sections.rs). The plan is four rectangles split at x = a and
// y = b/2 (so that the load point is a vertex), extruded in m layers.
//
//   z                       "load" (a, b/2, h)
//   |   +------------------o------------------+       "top": z = h
//   |  /|                                    /|
//   | +-------------------------------------+ |
//   | | |          beam                     | |
//   | | o "B" (0, b, 0)                     | +
//   | |/                                    |/
//   +-o-------------------------------------o---- x
//   "A" (0, 0, 0)                      "C" (L, 0, 0)
//
// Hexahedra, n along the span, m across the width and through the depth
// (m even).

DefineConstant[ L = {4.0, Name "Parameters/span"} ];
DefineConstant[ b = {0.4, Name "Parameters/width"} ];
DefineConstant[ h = {0.4, Name "Parameters/depth"} ];
DefineConstant[ a = {1.0, Name "Parameters/load point from the end x = 0"} ];
DefineConstant[ n = {20, Name "Parameters/elements along the span"} ];
DefineConstant[ m = {2, Name "Parameters/elements across (even)"} ];

xs[] = {0, a, L};
ys[] = {0, b / 2, b};
For i In {0:2}
  For j In {0:2}
    Point(1 + 3 * i + j) = {xs[i], ys[j], 0};
  EndFor
EndFor
For i In {0:1}
  For j In {0:2}
    Line(100 + 3 * i + j) = {1 + 3 * i + j, 1 + 3 * (i + 1) + j};
  EndFor
EndFor
For i In {0:2}
  For j In {0:1}
    Line(200 + 2 * i + j) = {1 + 3 * i + j, 2 + 3 * i + j};
  EndFor
EndFor
For i In {0:1}
  For j In {0:1}
    Curve Loop(300 + 2 * i + j) = {100 + 3 * i + j, 200 + 2 * (i + 1) + j, -(101 + 3 * i + j), -(200 + 2 * i + j)};
    Plane Surface(300 + 2 * i + j) = {300 + 2 * i + j};
  EndFor
EndFor
Transfinite Curve{100, 101, 102} = Round(n * a / L) + 1;
Transfinite Curve{103, 104, 105} = Round(n * (L - a) / L) + 1;
Transfinite Curve{200:205} = m / 2 + 1;
Transfinite Surface{300:303};
Recombine Surface{300:303};
out[] = Extrude {0, 0, h} { Surface{300:303}; Layers{m}; Recombine; };

e = 1e-6;
Physical Volume("beam") = {out[1], out[7], out[13], out[19]};
Physical Point("load") = Point In BoundingBox{a - e, b / 2 - e, h - e, a + e, b / 2 + e, h + e};
Physical Point("A") = Point In BoundingBox{-e, -e, -e, e, e, e};
Physical Point("B") = Point In BoundingBox{-e, b - e, -e, e, b + e, e};
Physical Point("C") = Point In BoundingBox{L - e, -e, -e, L + e, e, e};
Physical Surface("top") = Surface In BoundingBox{-e, -e, h - e, L + e, b + e, h + e};
