// patch_hex.geo -- the domain of the 3D patch tests (tests/patch.rs), after
// MacNeal and Harder's distorted patch: a hexahedron whose six planar faces
// are pairwise non-parallel, cut into seven hexahedral blocks by an irregular
// inner hexahedron (corners 9-16), each block joined to the outside face it
// faces.
//
//            8 +-----------+ 7        bottom 1234 in z = 0 (a general
//             /|   top    /|          quadrilateral); the four sides lie in
//          5 +-----------+ 6          planes through the apex (1.8, 1.4, 9);
//            | |  9..16  | |          the top 5678 in the tilted plane
//            | 4 +-------|-+ 3        z = 2.5 + 0.12 x - 0.08 y.
//            |/  bottom  |/
//          1 +-----------+ 2          face_IJKL: one physical surface per face
//                                     A, B, C = points 1, 2, 4 (3-2-1 support)
//
// hexes = 0: unstructured tetrahedra of size lc (irregular by nature);
// hexes = 1: every block a transfinite n x n x n grid of hexahedra (n = 1 is
//            MacNeal and Harder's seven-element patch), none a parallelepiped.
// mixed = 1: the inner block a transfinite n x n x n grid of hexahedra, the
//            six around it tetrahedra, with a pyramid on each quadrangle of
//            the inner block's faces (a hex-dominant core glued to a
//            tetrahedral region).
// serendipity = 1 makes `gmsh -order 2` write hex20 instead of hex27.
// Second-order nodes sit at mid-edge (Mesh.SecondOrderLinear): every
// element has straight edges.
//
// The top corners (bottom corners moved towards the apex onto the top plane)
// are printed in full so that the faces are planar to round-off;
// tests/patch.rs reads the Point coordinates to compute the face normals:
// keep them literal numbers.

DefineConstant[ hexes = {0, Name "Parameters/hexahedra"} ];
DefineConstant[ serendipity = {0, Name "Parameters/serendipity"} ];
DefineConstant[ lc = {0.9, Name "Parameters/tetrahedron size"} ];
DefineConstant[ n = {1, Name "Parameters/hexahedra per block edge"} ];
DefineConstant[ mixed = {0, Name "Parameters/hexahedral core in tetrahedra"} ];

Point(1) = {0.0, 0.0, 0.0, lc};
Point(2) = {4.0, 0.3, 0.0, lc};
Point(3) = {3.6, 3.2, 0.0, lc};
Point(4) = {0.3, 2.7, 0.0, lc};
Point(5) = {0.5058453237410074, 0.3934352517985613, 2.529226618705037, lc};
Point(6) = {3.3046193327630458, 0.6476903336184773, 2.8447390932420866, lc};
Point(7) = {3.0690476190476192, 2.6690476190476193, 2.654761904761904, lc};
Point(8) = {0.6992657182193669, 2.353969710876549, 2.395594309316201, lc};
Point(9) = {0.9, 0.7, 0.6, lc};
Point(10) = {2.9, 0.8, 0.8, lc};
Point(11) = {2.7, 2.2, 0.7, lc};
Point(12) = {1.1, 2.0, 0.9, lc};
Point(13) = {1.0, 0.9, 1.8, lc};
Point(14) = {2.6, 0.9, 1.9, lc};
Point(15) = {2.4, 2.0, 1.7, lc};
Point(16) = {1.2, 1.8, 1.6, lc};

// outer edges 1-12, inner edges 13-24, corner i to inner corner i + 8: 25-32
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Line(5) = {5, 6};
Line(6) = {6, 7};
Line(7) = {7, 8};
Line(8) = {8, 5};
Line(9) = {1, 5};
Line(10) = {2, 6};
Line(11) = {3, 7};
Line(12) = {4, 8};
Line(13) = {9, 10};
Line(14) = {10, 11};
Line(15) = {11, 12};
Line(16) = {12, 9};
Line(17) = {13, 14};
Line(18) = {14, 15};
Line(19) = {15, 16};
Line(20) = {16, 13};
Line(21) = {9, 13};
Line(22) = {10, 14};
Line(23) = {11, 15};
Line(24) = {12, 16};
Line(25) = {1, 9};
Line(26) = {2, 10};
Line(27) = {3, 11};
Line(28) = {4, 12};
Line(29) = {5, 13};
Line(30) = {6, 14};
Line(31) = {7, 15};
Line(32) = {8, 16};

// the outer faces 1-6 (planar), the inner faces 7-12, the surfaces
// joining an outer edge to its inner edge 13-24
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Curve Loop(2) = {5, 6, 7, 8};
Plane Surface(2) = {2};
Curve Loop(3) = {1, 10, -5, -9};
Plane Surface(3) = {3};
Curve Loop(4) = {2, 11, -6, -10};
Plane Surface(4) = {4};
Curve Loop(5) = {3, 12, -7, -11};
Plane Surface(5) = {5};
Curve Loop(6) = {4, 9, -8, -12};
Plane Surface(6) = {6};
Curve Loop(7) = {13, 14, 15, 16};
Surface(7) = {7};
Curve Loop(8) = {17, 18, 19, 20};
Surface(8) = {8};
Curve Loop(9) = {13, 22, -17, -21};
Surface(9) = {9};
Curve Loop(10) = {14, 23, -18, -22};
Surface(10) = {10};
Curve Loop(11) = {15, 24, -19, -23};
Surface(11) = {11};
Curve Loop(12) = {16, 21, -20, -24};
Surface(12) = {12};
Curve Loop(13) = {1, 26, -13, -25};
Surface(13) = {13};
Curve Loop(14) = {2, 27, -14, -26};
Surface(14) = {14};
Curve Loop(15) = {3, 28, -15, -27};
Surface(15) = {15};
Curve Loop(16) = {4, 25, -16, -28};
Surface(16) = {16};
Curve Loop(17) = {5, 30, -17, -29};
Surface(17) = {17};
Curve Loop(18) = {6, 31, -18, -30};
Surface(18) = {18};
Curve Loop(19) = {7, 32, -19, -31};
Surface(19) = {19};
Curve Loop(20) = {8, 29, -20, -32};
Surface(20) = {20};
Curve Loop(21) = {9, 29, -21, -25};
Surface(21) = {21};
Curve Loop(22) = {10, 30, -22, -26};
Surface(22) = {22};
Curve Loop(23) = {11, 31, -23, -27};
Surface(23) = {23};
Curve Loop(24) = {12, 32, -24, -28};
Surface(24) = {24};

// volume 1: the inner hexahedron; 2-7: between an outer face and its inner face
Surface Loop(1) = {7, 8, 9, 10, 11, 12};
Volume(1) = {1};
Surface Loop(2) = {1, 7, 13, 14, 15, 16};
Volume(2) = {2};
Surface Loop(3) = {2, 8, 17, 18, 19, 20};
Volume(3) = {3};
Surface Loop(4) = {3, 9, 13, 22, 17, 21};
Volume(4) = {4};
Surface Loop(5) = {4, 10, 14, 23, 18, 22};
Volume(5) = {5};
Surface Loop(6) = {5, 11, 15, 24, 19, 23};
Volume(6) = {6};
Surface Loop(7) = {6, 12, 16, 21, 20, 24};
Volume(7) = {7};

If (hexes)
  Transfinite Curve{1:32} = n + 1;
  Transfinite Surface{1:24};
  Recombine Surface{1:24};
  Transfinite Volume{1:7};
ElseIf (mixed)
  Transfinite Curve{13:24} = n + 1;
  Transfinite Surface{7:12};
  Recombine Surface{7:12};
  Transfinite Volume{1};
EndIf
Mesh.SecondOrderIncomplete = serendipity;
// the inner faces are bilinear (warped) patches: keep the second-order
// nodes on straight edges so that tetrahedra stay affine
Mesh.SecondOrderLinear = 1;

Physical Volume("body") = {1:7};
Physical Surface("face_1234") = {1};
Physical Surface("face_5678") = {2};
Physical Surface("face_1265") = {3};
Physical Surface("face_2376") = {4};
Physical Surface("face_3487") = {5};
Physical Surface("face_4158") = {6};
Physical Point("A") = {1};
Physical Point("B") = {2};
Physical Point("C") = {4};
