// lame_slice.geo -- a slice of Lame's thick-walled cylinder for the 3D
// convergence study of tests/lame.rs: the quarter annulus a <= r <= b,
// 0 <= theta <= 90 degrees, extruded one element layer of thickness lc
// along z, meshed with structured hexahedra.
//
//        y
//        |
//      b +.                 inner: r = a (pressure), outer: r = b
//        |   .              x0: x = 0, y0: y = 0 (symmetry)
//      a +.     .           z0: z = 0, z1: z = lc (w = 0 on both: plane strain)
//        |  .     .
//        +---+-----+--- x
//            a     b
//
// (b - a)/lc hexahedra radially, about (pi/2) r_mean / lc around.

DefineConstant[ lc = {0.25, Min 0.01, Max 1, Name "Parameters/element size"} ];
a = 3.0;
b = 5.0;

Point(1) = {0, 0, 0};
Point(2) = {a, 0, 0};
Point(3) = {b, 0, 0};
Point(4) = {0, b, 0};
Point(5) = {0, a, 0};

Line(1) = {2, 3};          // y = 0
Circle(2) = {3, 1, 4};     // r = b
Line(3) = {4, 5};          // x = 0
Circle(4) = {5, 1, 2};     // r = a
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};

nr = Ceil((b - a) / lc) + 1;
nt = Ceil(Pi / 2 * (a + b) / 2 / lc) + 1;
Transfinite Curve{1, 3} = nr;
Transfinite Curve{2, 4} = nt;
Transfinite Surface{1};
Recombine Surface{1};

// ex[0]: the top z = lc, ex[1]: the volume, ex[2..5]: the faces swept by curves 1..4
ex[] = Extrude {0, 0, lc} { Surface{1}; Layers{1}; Recombine; };

Physical Volume("body") = {ex[1]};
Physical Surface("y0") = {ex[2]};
Physical Surface("outer") = {ex[3]};
Physical Surface("x0") = {ex[4]};
Physical Surface("inner") = {ex[5]};
Physical Surface("z0") = {1};
Physical Surface("z1") = {ex[0]};
