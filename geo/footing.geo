// footing.geo -- a stiff foundation beam on an elastic ground block, loaded
// eccentrically through a short bearing plate on its top (a column load V at
// eccentricity e from the beam's centre). The beam-ground interface takes no
// tension: beyond the middle third (e > B/6) the beam's far edge lifts off.
//
// Sample runs:
//   subcontact solve geo/footing.toml                  (e = B/3, quad9)
//   setnumber = { e = 0.5 } in footing.toml            (e = B/4)
//   setnumber = { depth = 0.25 } in footing.toml       (a thin stratum on rock)
//
//                      plate (V at x = e, width wp)
//                        vvv
//         -B/2  +-----------------+  B/2     beam: B wide, t deep
//               |      beam       |
//   +-----------+===== base ======+-----------+  y = 0
//   |side                                  side|  ground: W wide, `depth` deep
//   |                 ground                   |  sides: held in x
//   |                                          |  bottom: held in x and y
//   +------------------------------------------+  y = -depth
//  -W/2                  bottom               W/2
//
// The contact curve "base" is shared by both bodies and meshed with
// uniform elements of size lc (B / lc of them); the ground's elements grow
// from lc at the beam to lc_far a few B away. Quadrilaterals everywhere.

DefineConstant[
  lc     = {0.05, Min 0.005, Max 0.5, Name "Parameters/element size at the beam"},
  lc_far = {1.0, Min 0.05, Max 5, Name "Parameters/element size far away"},
  e      = {0.6666666666666666, Min -0.9, Max 0.9, Name "Parameters/eccentricity of the load"},
  depth  = {10.0, Min 0.05, Max 100, Name "Parameters/depth of the ground"}
];
B  = 2.0;    // beam width
t  = 0.5;    // beam depth
W  = 10 * B; // ground width
wp = 0.2;    // bearing plate width (the load's footprint)

If (Fabs(e) + wp / 2 > B / 2)
  Error("footing.geo: the plate (e = %g, width %g) must lie on the beam's top (|e| <= %g)", e, wp, B / 2 - wp / 2);
EndIf

// 1. Ground: a rectangle whose top carries the contact curve.
Point(1) = {-W / 2, -depth, 0};
Point(2) = { W / 2, -depth, 0};
Point(3) = { W / 2, 0, 0};
Point(4) = { B / 2, 0, 0};
Point(5) = {-B / 2, 0, 0};
Point(6) = {-W / 2, 0, 0};
Line(1) = {1, 2};   // bottom
Line(2) = {2, 3};   // right side
Line(3) = {3, 4};   // free ground surface, right
Line(4) = {4, 5};   // base: the contact, from the loaded edge to the far edge for e > 0
Line(5) = {5, 6};   // free ground surface, left
Line(6) = {6, 1};   // left side
Curve Loop(1) = {1, 2, 3, 4, 5, 6};
Plane Surface(1) = {1};

// 2. Beam: its top split at the plate.
Point(7)  = { B / 2, t, 0};
Point(8)  = {e + wp / 2, t, 0};
Point(9)  = {e - wp / 2, t, 0};
Point(10) = {-B / 2, t, 0};
Line(7)  = {4, 7};
Line(8)  = {7, 8};
Line(9)  = {8, 9};  // the plate
Line(10) = {9, 10};
Line(11) = {10, 5};
Curve Loop(2) = {-4, 7, 8, 9, 10, 11};
Plane Surface(2) = {2};

// 3. Sizes: uniform along the contact, graded into the ground.
Transfinite Curve{4} = Ceil(B / lc) + 1;
Field[1] = Distance;
Field[1].CurvesList = {4};
Field[1].NumPointsPerCurve = 200;
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = lc;
Field[2].SizeMax = lc_far;
Field[2].DistMin = B / 4;
Field[2].DistMax = 3 * B;
Background Field = 2;
Mesh.CharacteristicLengthExtendFromBoundary = 0;
Mesh.CharacteristicLengthFromPoints = 0;
Recombine Surface{1, 2};

Physical Surface("ground") = {1};
Physical Surface("beam") = {2};
Physical Curve("base") = {4};
Physical Curve("plate") = {9};
Physical Curve("bottom") = {1};
Physical Curve("sides") = {2, 6};
