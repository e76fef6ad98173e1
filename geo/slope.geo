// slope.geo -- a rock slope with a tension crack behind its crest, the
// block between the slope face, the crack and a sliding plane daylighting
// at the toe (Hoek & Bray, Rock Slope Engineering, planar failure, the
// tension crack in the upper slope surface). The sliding plane is the
// contact "plane"; the crack is open, its face "crack" a free surface the
// water in it presses on.
//
// Sample run:
//   subcontact solve geo/slope.toml      (make slope)
//
//                      x_c
//          crest       |  crack (free face "crack"), depth z
//   y = H  +-----------+  +------------------+  top
//         /   block    |  |                  |
//        /  psi_f      +..|  sliding plane   |
//       /          ..''   |  "plane" at psi_p|
//  toe +........''        |      rock        |
//   y = 0 ----+''         |                  |
//             |   rock (below the plane, behind the crack; held at its
//             |   bottom and sides)
//
// Units: m. The block is held by the plane alone. split = 1 draws the
// plane as two coincident curves ("plane_block", "plane_rock"): the
// contact is then groups = [..], and each face can take a [[loads]]
// pressure of its own (the way water was put in a joint before
// `[[contacts]] water`: tests/water.rs compares the two).

DefineConstant[ lc = {0.5, Min 0.05, Max 5, Name "Parameters/element size"} ];
DefineConstant[ H = {12.0, Name "Parameters/slope height"} ];
DefineConstant[ psi_f = {60.0, Name "Parameters/slope face angle (degrees)"} ];
DefineConstant[ psi_p = {30.0, Name "Parameters/sliding plane angle (degrees)"} ];
DefineConstant[ z = {4.0, Name "Parameters/tension crack depth"} ];
DefineConstant[ gap = {0.5, Name "Parameters/width of the tension crack"} ];
DefineConstant[ split = {0, Name "Parameters/the plane as two coincident curves"} ];

tp = Tan(psi_p * Pi / 180);
xf = H / Tan(psi_f * Pi / 180);   // the crest
xc = (H - z) / tp;                // the crack, where the plane meets it
xr = xc + gap + 2 * H;            // the rock's far side
yb = -H;                          // the rock's bottom
xl = -H;                          // the ground in front of the toe

// the block
Point(1) = {0, 0, 0, lc};
Point(2) = {xc, H - z, 0, lc};
Point(3) = {xc, H, 0, lc};
Point(4) = {xf, H, 0, lc};
Line(1) = {1, 2};     // the sliding plane
Line(2) = {2, 3};     // the crack's face
Line(3) = {3, 4};     // the top behind the crest
Line(4) = {4, 1};     // the slope face
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};

// the rock: below the plane, behind the crack
Point(5) = {xl, 0, 0, 2 * lc};
Point(6) = {xl, yb, 0, 4 * lc};
Point(7) = {xr, yb, 0, 4 * lc};
Point(8) = {xr, H, 0, 2 * lc};
Point(9) = {xc + gap, H, 0, lc};
Point(10) = {xc + gap, H - z, 0, lc};
pa = 1; pb = 2; plane = 1;
If (split)
  // the rock's own copy of the plane
  Point(11) = {0, 0, 0, lc};
  Point(12) = {xc, H - z, 0, lc};
  Line(11) = {11, 12};
  pa = 11; pb = 12; plane = 11;
EndIf
Line(5) = {5, pa};
Line(6) = {6, 5};
Line(7) = {7, 6};
Line(8) = {8, 7};
Line(9) = {9, 8};
Line(10) = {10, 9};
Line(12) = {pb, 10};
Curve Loop(2) = {-6, -7, -8, -9, -10, -12, -plane, -5};
Plane Surface(2) = {2};

Physical Surface("block") = {1};
Physical Surface("rock") = {2};
If (split)
  Physical Curve("plane_block") = {1};
  Physical Curve("plane_rock") = {11};
Else
  Physical Curve("plane") = {1};
EndIf
Physical Curve("crack") = {2};
Physical Curve("rock_bottom") = {7};
Physical Curve("rock_sides") = {6, 8};
