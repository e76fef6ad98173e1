// beam2d.geo -- a beam of span L and depth h on two point supports, a
// point on its top at x = a (tests/point_loads.rs, tests/sections.rs).
//
//   y            "load" (a, h)
//   |  +-----------o-----------------------+  h      "top": y = h
//   |  |                 beam              |
//   +--o-----------------------------------o-- x    "bottom": y = 0
//     "pin" (0, 0)                     "roller" (L, 0)
//
// Transfinite quadrilaterals, n along the span and m through the depth.

DefineConstant[ L = {4.0, Name "Parameters/span"} ];
DefineConstant[ h = {0.4, Name "Parameters/depth"} ];
DefineConstant[ a = {1.0, Name "Parameters/load point from the pin"} ];
DefineConstant[ n = {40, Name "Parameters/elements along the span"} ];
DefineConstant[ m = {4, Name "Parameters/elements through the depth"} ];

Point(1) = {0, 0, 0};
Point(2) = {L, 0, 0};
Point(3) = {L, h, 0};
Point(4) = {a, h, 0};
Point(5) = {0, h, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 5};
Line(5) = {5, 1};
Curve Loop(1) = {1, 2, 3, 4, 5};
Plane Surface(1) = {1};
Transfinite Curve{1} = n + 1;
Transfinite Curve{2, 5} = m + 1;
Transfinite Curve{3} = Round(n * (L - a) / L) + 1;
Transfinite Curve{4} = Round(n * a / L) + 1;
Transfinite Surface{1} = {1, 2, 3, 5};
Recombine Surface{1};

Physical Surface("beam") = {1};
Physical Point("pin") = {1};
Physical Point("roller") = {2};
Physical Point("load") = {4};
Physical Curve("top") = {3, 4};
Physical Curve("bottom") = {1};
