// beam_on_layer.geo -- a free beam (length L, depth d) on a thin elastic
// layer (depth h) on rigid ground, a point on its top at the middle
// (tests/sections.rs: Hetényi's beam on an elastic foundation).
//
//   y                  "load" (0, d)
//   |   +-----------------o-----------------+  d
//   |   |                beam               |
//   0   +===================================+  "base": contact (shared curve)
//       |                layer              |
//  -h   +-----------------------------------+  "bottom": held
//     -L/2                0                L/2
//
// Transfinite quadrilaterals of size lc along the beam, m through its
// depth, one through the layer.

DefineConstant[ L = {20.0, Name "Parameters/beam length"} ];
DefineConstant[ d = {0.5, Name "Parameters/beam depth"} ];
DefineConstant[ h = {0.1, Name "Parameters/layer depth"} ];
DefineConstant[ lc = {0.125, Name "Parameters/element length"} ];
DefineConstant[ m = {4, Name "Parameters/elements through the beam"} ];

Point(1) = {-L / 2, -h, 0};
Point(2) = {L / 2, -h, 0};
Point(3) = {L / 2, 0, 0};
Point(4) = {-L / 2, 0, 0};
Point(5) = {L / 2, d, 0};
Point(6) = {0, d, 0};
Point(7) = {-L / 2, d, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Line(5) = {3, 5};
Line(6) = {5, 6};
Line(7) = {6, 7};
Line(8) = {7, 4};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Curve Loop(2) = {-3, 5, 6, 7, 8};
Plane Surface(2) = {2};
n = Round(L / lc);
Transfinite Curve{1, 3} = n + 1;
Transfinite Curve{6, 7} = n / 2 + 1;
Transfinite Curve{2, 4} = 2;
Transfinite Curve{5, 8} = m + 1;
Transfinite Surface{1};
Transfinite Surface{2} = {4, 3, 5, 7};
Recombine Surface{1, 2};

Physical Surface("layer") = {1};
Physical Surface("beam") = {2};
Physical Curve("base") = {3};
Physical Curve("bottom") = {1};
Physical Curve("top") = {6, 7};
Physical Point("load") = {6};
