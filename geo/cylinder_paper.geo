// cylinder_paper.geo -- the seed paper's own mesh of its example: 30 eight-node
// hexahedra, 5 radial x 6 circumferential x 1 through z = 0..1, the quarter
// cylinder cut at 45 degrees into body_1 (0-45 degrees) and body_2 (45-90).
// 84 mesh nodes; the 12 nodes of the cut A-A are split into 12 contact pairs.
//
// Sample run:
//   subcontact solve geo/cylinder_paper.toml
//
// Groups: body_1, body_2 (volumes); A-A (the cut), inner (r = 3, pressure),
// outer (r = 5), symmetry_x0 (x = 0), symmetry_y0 (y = 0), faces_z (z = 0
// and z = 1, w = 0: plane strain).

a = 3.0;
b = 5.0;

Point(1) = {0, 0, 0};
Point(2) = {a, 0, 0};
Point(3) = {b, 0, 0};
Point(4) = {a * Cos(Pi/4), a * Sin(Pi/4), 0};
Point(5) = {b * Cos(Pi/4), b * Sin(Pi/4), 0};
Point(6) = {0, a, 0};
Point(7) = {0, b, 0};

Line(1) = {2, 3};
Circle(2) = {3, 1, 5};
Line(3) = {5, 4};
Circle(4) = {4, 1, 2};
Circle(5) = {5, 1, 7};
Line(6) = {7, 6};
Circle(7) = {6, 1, 4};

Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Curve Loop(2) = {-3, 5, 6, 7};
Plane Surface(2) = {2};

Transfinite Curve{1, 3, 6} = 6;     // 5 elements radially
Transfinite Curve{2, 4, 5, 7} = 4;  // 3 elements around each body
Transfinite Surface{1, 2};
Recombine Surface{1, 2};

out1[] = Extrude {0, 0, 1} { Surface{1}; Layers{1}; Recombine; };
out2[] = Extrude {0, 0, 1} { Surface{2}; Layers{1}; Recombine; };
// out[0] top, out[1] volume, out[2..5] the sides from curves 1,2,3,4 (resp. -3,5,6,7)

Physical Volume("body_1") = {out1[1]};
Physical Volume("body_2") = {out2[1]};
Physical Surface("A-A") = {out1[4]};
Physical Surface("inner") = {out1[5], out2[5]};
Physical Surface("outer") = {out1[3], out2[3]};
Physical Surface("symmetry_y0") = {out1[2]};
Physical Surface("symmetry_x0") = {out2[4]};
Physical Surface("faces_z") = {1, 2, out1[0], out2[0]};
