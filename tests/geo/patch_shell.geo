// patch_shell.geo -- the outer shell of tests/geo/patch_hex.geo (MacNeal and
// Harder's distorted hexahedron: six planar faces, no two parallel) cut into
// two blocks, for the patch tests of prisms and pyramids (tests/patch.rs).
//
//            8 +------12-----+ 7      bottom 1234 in z = 0; the sides in
//             /|     /      /|        planes through the apex (1.8, 1.4, 9);
//          5 +-----11------+ 6        the top 5678 tilted. The cut 9-10-12-11
//            | |   | |     | |        (a warped surface) splits the shell
//            | 4 +-|---10--|-+ 3      into block A (1 9 10 4 / 5 11 12 8) and
//            |/    |/      |/         block B (9 2 3 10 / 11 6 7 12); points
//          1 +-----9-------+ 2        9-12 lie on the outer edges.
//
// cells = 1: both blocks transfinite n x n x n, their caps (the bottom and
//            top) triangulated: every cell a prism, none with parallel
//            triangles (the caps are not parallel) -> prism6/15/18;
// cells = 2: every outer surface a transfinite grid of quadrangles, the
//            volumes unstructured tetrahedra: gmsh puts a pyramid on each
//            quadrangle -> pyramid5/13/14 among tetrahedra (the cut stays
//            triangulated: gmsh 4.8.4 cannot put pyramids on both sides of
//            a quadrangle);
// cells = 3: block A transfinite hexahedra, block B transfinite prisms
//            (as in 1): a hexahedron meets a prism on every quadrangle of
//            the cut -> hex8 + prism6, hex27 + prism18, hex20 + prism15.
// serendipity = 1 makes `gmsh -order 2` write the incomplete kinds (prism15,
// pyramid13, hex20). Second-order nodes sit at mid-edge
// (Mesh.SecondOrderLinear): straight-edged cells.
//
// tests/patch.rs reads the Point coordinates (literal numbers) for the face
// normals; the faces carry the physical names of patch_hex.geo.

DefineConstant[ cells = {1, Name "Parameters/cells"} ];
DefineConstant[ serendipity = {0, Name "Parameters/serendipity"} ];
DefineConstant[ lc = {0.9, Name "Parameters/tetrahedron size"} ];
DefineConstant[ n = {2, Name "Parameters/cells per block edge"} ];

Point(1) = {0.0, 0.0, 0.0, lc};
Point(2) = {4.0, 0.3, 0.0, lc};
Point(3) = {3.6, 3.2, 0.0, lc};
Point(4) = {0.3, 2.7, 0.0, lc};
Point(5) = {0.5058453237410074, 0.3934352517985613, 2.529226618705037, lc};
Point(6) = {3.3046193327630458, 0.6476903336184773, 2.8447390932420866, lc};
Point(7) = {3.0690476190476192, 2.6690476190476193, 2.654761904761904, lc};
Point(8) = {0.6992657182193669, 2.353969710876549, 2.395594309316201, lc};
Point(9) = {1.8, 0.135, 0.0, lc};
Point(10) = {2.115, 2.975, 0.0, lc};
Point(11) = {1.6253549273498227, 0.4951372845265277, 2.655431608519857, lc};
Point(12) = {1.884156668633493, 2.511508664962084, 2.5251781070390527, lc};

Line(1) = {1, 9};
Line(2) = {9, 2};
Line(3) = {2, 3};
Line(4) = {3, 10};
Line(5) = {10, 4};
Line(6) = {4, 1};
Line(7) = {5, 11};
Line(8) = {11, 6};
Line(9) = {6, 7};
Line(10) = {7, 12};
Line(11) = {12, 8};
Line(12) = {8, 5};
Line(13) = {1, 5};
Line(14) = {2, 6};
Line(15) = {3, 7};
Line(16) = {4, 8};
Line(17) = {9, 10};
Line(18) = {11, 12};
Line(19) = {9, 11};
Line(20) = {10, 12};

// bottom (1, 2), top (3, 4), front (5, 6), back (7, 8), left 9, right 10, cut 11
Curve Loop(1) = {1, 17, 5, 6};
Plane Surface(1) = {1};
Curve Loop(2) = {2, 3, 4, -17};
Plane Surface(2) = {2};
Curve Loop(3) = {7, 18, 11, 12};
Plane Surface(3) = {3};
Curve Loop(4) = {8, 9, 10, -18};
Plane Surface(4) = {4};
Curve Loop(5) = {1, 19, -7, -13};
Plane Surface(5) = {5};
Curve Loop(6) = {2, 14, -8, -19};
Plane Surface(6) = {6};
Curve Loop(7) = {-5, 20, 11, -16};
Plane Surface(7) = {7};
Curve Loop(8) = {-4, 15, 10, -20};
Plane Surface(8) = {8};
Curve Loop(9) = {6, 13, -12, -16};
Plane Surface(9) = {9};
Curve Loop(10) = {3, 15, -9, -14};
Plane Surface(10) = {10};
Curve Loop(11) = {17, 20, -18, -19};
Surface(11) = {11};

Surface Loop(1) = {1, 3, 5, 7, 9, 11};
Volume(1) = {1};
Surface Loop(2) = {2, 4, 6, 8, 10, 11};
Volume(2) = {2};

Transfinite Curve{1:20} = n + 1;
Transfinite Surface{1:11};
If (cells == 1)
  Recombine Surface{5:11};
  Transfinite Volume{1, 2};
ElseIf (cells == 2)
  Recombine Surface{1:10};
Else
  Recombine Surface{1, 3, 5:11};
  Transfinite Volume{1, 2};
EndIf
Mesh.SecondOrderIncomplete = serendipity;
Mesh.SecondOrderLinear = 1;

Physical Volume("body") = {1, 2};
Physical Surface("face_1234") = {1, 2};
Physical Surface("face_5678") = {3, 4};
Physical Surface("face_1265") = {5, 6};
Physical Surface("face_2376") = {10};
Physical Surface("face_3487") = {7, 8};
Physical Surface("face_4158") = {9};
Physical Point("A") = {1};
Physical Point("B") = {2};
Physical Point("C") = {4};
