// lame_revolved.geo -- Lame's thick-walled cylinder for the convergence
// study of prisms in tests/lame.rs: the meridian rectangle a <= r <= b,
// 0 <= z <= lc (in the plane y = 0), cut into structured triangles, revolved
// a quarter turn about the z axis in layers: prisms whose triangles lie in
// meridian planes and whose third direction runs around the axis, so the
// displacement u_r(r) (cos t, sin t, 0) varies along all three of their
// reference directions.
//
//        y
//        |
//      b +.                 inner: r = a (pressure), outer: r = b
//        |   .              x0: the quarter turn's end (x = 0), y0: the
//      a +.     .               meridian itself (y = 0)
//        |  .     .         z0: z = 0, z1: z = lc (w = 0 on both: plane strain)
//        +---+-----+--- x
//            a     b
//
// (b - a)/lc triangle pairs radially, one row in z, about (pi/2) r_mean / lc
// layers around. serendipity = 1 makes `gmsh -order 2` write prism15.

DefineConstant[ lc = {0.25, Min 0.01, Max 1, Name "Parameters/element size"} ];
DefineConstant[ serendipity = {0, Name "Parameters/serendipity"} ];
a = 3.0;
b = 5.0;

Point(1) = {a, 0, 0};
Point(2) = {b, 0, 0};
Point(3) = {b, 0, lc};
Point(4) = {a, 0, lc};
Line(1) = {1, 2};          // z = 0
Line(2) = {2, 3};          // r = b
Line(3) = {3, 4};          // z = lc
Line(4) = {4, 1};          // r = a
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};

nr = Ceil((b - a) / lc) + 1;
nt = Ceil(Pi / 2 * (a + b) / 2 / lc);
Transfinite Curve{1, 3} = nr;
Transfinite Curve{2, 4} = 2;
Transfinite Surface{1};
Mesh.SecondOrderIncomplete = serendipity;

// ex[0]: the end of the turn (x = 0), ex[1]: the volume, ex[2..5]: the faces
// swept by curves 1..4
ex[] = Extrude { {0, 0, 1}, {0, 0, 0}, Pi / 2 } { Surface{1}; Layers{nt}; Recombine; };

Physical Volume("body") = {ex[1]};
Physical Surface("y0") = {1};
Physical Surface("x0") = {ex[0]};
Physical Surface("z0") = {ex[2]};
Physical Surface("outer") = {ex[3]};
Physical Surface("z1") = {ex[4]};
Physical Surface("inner") = {ex[5]};
