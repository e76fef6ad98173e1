// patch_curved_3d.geo -- the domain of the 3D hydrostatic patch test
// (tests/patch.rs): the annular sector of patch_curved.geo (radii 2 and 4,
// 15 to 75 degrees) extruded 1.5 along z, so that the quadratic elements
// along the two cylindrical faces are curved.
//
// hexes = 0: unstructured tetrahedra of size lc;
// hexes = 1: hexahedra, n radially (graded) x 2 n around x 2 layers;
// prisms = 1: the plan triangulated (size lc), extruded in 2 layers: prisms.
// serendipity = 1 makes `gmsh -order 2` write hex20 instead of hex27.
//
// boundary: all six faces (pressure); A, B, C = points 1, 2, 4 on z = 0
// (3-2-1 support).

DefineConstant[ hexes = {0, Name "Parameters/hexahedra"} ];
DefineConstant[ serendipity = {0, Name "Parameters/serendipity"} ];
DefineConstant[ lc = {0.7, Name "Parameters/tetrahedron size"} ];
DefineConstant[ n = {2, Name "Parameters/hexahedra radially"} ];
DefineConstant[ prisms = {0, Name "Parameters/prisms"} ];

r1 = 2.0;
r2 = 4.0;
t1 = 15 * Pi / 180;
t2 = 75 * Pi / 180;
Point(1) = {r1 * Cos(t1), r1 * Sin(t1), 0, lc};
Point(2) = {r2 * Cos(t1), r2 * Sin(t1), 0, lc};
Point(3) = {r2 * Cos(t2), r2 * Sin(t2), 0, lc};
Point(4) = {r1 * Cos(t2), r1 * Sin(t2), 0, lc};
Point(5) = {0, 0, 0, lc};

Line(1) = {1, 2};
Circle(2) = {2, 5, 3};
Line(3) = {3, 4};
Circle(4) = {4, 5, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};

If (hexes)
  Transfinite Curve{1} = n + 1 Using Progression 1.3;
  Transfinite Curve{3} = n + 1;
  Transfinite Curve{2, 4} = 2 * n + 1;
  Transfinite Surface{1};
  Recombine Surface{1};
  ex[] = Extrude {0, 0, 1.5} { Surface{1}; Layers{2}; Recombine; };
ElseIf (prisms)
  ex[] = Extrude {0, 0, 1.5} { Surface{1}; Layers{2}; Recombine; };
Else
  ex[] = Extrude {0, 0, 1.5} { Surface{1}; };
EndIf
Mesh.SecondOrderIncomplete = serendipity;

// ex[0]: the top face, ex[1]: the volume, ex[2..5]: the sides
Physical Volume("body") = {ex[1]};
Physical Surface("boundary") = {1, ex[0], ex[2], ex[3], ex[4], ex[5]};
Physical Point("A") = {1};
Physical Point("B") = {2};
Physical Point("C") = {4};
