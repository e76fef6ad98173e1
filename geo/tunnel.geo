// tunnel.geo -- a circular tunnel lining in a large block of rock, quarter
// model: the lining (middle-surface radius R, thickness t: r = ri .. ro =
// R -+ t/2) and the rock around it meet in contact along the excavation
// boundary r = ro; the rock reaches out to the square |x|, |y| <= D
// (default 200 = 40 R: the lining's bending is within 0.5 % of an infinite
// rock's; at D = 10 R it is 5-8 % off, whether the far boundary is loaded or
// held).
//
// Sample runs:
//   subcontact solve geo/tunnel.toml          (no slip; quad9, lc = 0.1, D = 200)
//   subcontact solve geo/tunnel_slip.toml     (full slip)
//   gmsh geo/tunnel.geo -2 -order 2 -setnumber lc 0.05     (mesh only)
//
//        y
//      D +-------------------------+  far_y (y = D)
//        |                      .  |
//        |   rock, block 2   .     |
//        |                .        |
//        |             .           |  far_x (x = D)
//        |          .   rock,      |
//     ro +-.     .      block 1    |
//     ri +. .  .                   |  interface: the arc r = ro (shared by
//        |lining.                  |  lining and rock: the contact)
//        +--+-+--------------------+--- x
//        0  ri ro                  D
//  symmetry_y0: y = 0 (lining and rock), symmetry_x0: x = 0
//
// Structured quadrilaterals everywhere: the lining has nl elements through
// its thickness and ceil((pi/4) ro / lc) around each eighth; the rock is cut
// along the 45-degree line into two four-sided blocks meshed node to node
// with the lining, graded in geometric progression from size lc at the
// lining to a few metres at the far boundary.

DefineConstant[ lc = {0.1, Min 0.005, Max 1, Name "Parameters/element size at the lining"} ];
DefineConstant[ nl = {4, Min 1, Max 20, Name "Parameters/elements through the lining"} ];
DefineConstant[ nr = {52, Min 4, Max 400, Name "Parameters/elements across the rock"} ];
DefineConstant[ R = {5.0, Name "Parameters/radius of the lining's middle surface"} ];
DefineConstant[ t = {0.125, Name "Parameters/lining thickness"} ];
DefineConstant[ D = {200.0, Name "Parameters/half width of the rock block"} ];
ri = R - t / 2;
ro = R + t / 2;
c45 = Cos(Pi / 4);

// 1. Points: centre, the lining's and the rock's corners.
Point(1) = {0, 0, 0};
Point(2) = {ri, 0, 0};
Point(3) = {ro, 0, 0};
Point(4) = {D, 0, 0};
Point(5) = {ri * c45, ri * c45, 0};
Point(6) = {ro * c45, ro * c45, 0};
Point(7) = {D, D, 0};
Point(8) = {0, ri, 0};
Point(9) = {0, ro, 0};
Point(10) = {0, D, 0};

// 2. Curves: arcs r = ri and r = ro in two eighths, radial lines, far edges.
Circle(1) = {2, 1, 5};     // inner arc, 0..45 degrees
Circle(2) = {5, 1, 8};     // inner arc, 45..90
Circle(3) = {3, 1, 6};     // interface, 0..45
Circle(4) = {6, 1, 9};     // interface, 45..90
Line(5) = {2, 3};          // lining end on y = 0
Line(6) = {5, 6};          // lining, 45 degrees
Line(7) = {8, 9};          // lining end on x = 0
Line(8) = {3, 4};          // rock on y = 0
Line(9) = {6, 7};          // rock, 45 degrees
Line(10) = {9, 10};        // rock on x = 0
Line(11) = {4, 7};         // far_x
Line(12) = {7, 10};        // far_y

// 3. Surfaces: two lining eighths, two rock blocks.
Curve Loop(1) = {5, 3, -6, -1};
Plane Surface(1) = {1};
Curve Loop(2) = {6, 4, -7, -2};
Plane Surface(2) = {2};
Curve Loop(3) = {8, 11, -9, -3};
Plane Surface(3) = {3};
Curve Loop(4) = {9, 12, -10, -4};
Plane Surface(4) = {4};

// 4. Divisions. Around: nt elements per eighth on every arc and far edge.
// Across the rock: nr elements growing geometrically from about lc; the
// growth factor q of a line of length L solves lc (q^nr - 1)/(q - 1) = L
// (fixed-point iteration q <- (1 + L (q - 1)/lc)^(1/nr), a contraction here).
nt = Ceil(Pi / 4 * ro / lc);
La = D - ro;
Ld = D * Sqrt(2) - ro;
qa = 1.2;
qd = 1.2;
For k In {1:200}
  qa = (1 + La * (qa - 1) / lc)^(1 / nr);
  qd = (1 + Ld * (qd - 1) / lc)^(1 / nr);
EndFor
Transfinite Curve{1, 2, 3, 4, 11, 12} = nt + 1;
Transfinite Curve{5, 6, 7} = nl + 1;
Transfinite Curve{8, 10} = nr + 1 Using Progression qa;   // all three run outwards
Transfinite Curve{9} = nr + 1 Using Progression qd;
Transfinite Surface{1, 2, 3, 4};
Recombine Surface{1, 2, 3, 4};

Physical Surface("lining") = {1, 2};
Physical Surface("rock") = {3, 4};
Physical Curve("interface") = {3, 4};
Physical Curve("symmetry_y0") = {5, 8};
Physical Curve("symmetry_x0") = {7, 10};
Physical Curve("far_x") = {11};
Physical Curve("far_y") = {12};
