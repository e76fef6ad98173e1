// planar_slope.geo -- Hoek & Bray's planar failure of a rock slope with a
// dry tension crack (Rock Slope Engineering, ch. 6): a block of rock on one
// sliding plane that daylights at the toe of the face, cut off behind the
// crest by a vertical tension crack.
//
//   y                       crack top  crack
//   |          crest +---------+       |
//   |  face  /        block    |  (free vertical face: the dry crack)
//   | (60)  /                 _+ crack bottom
//   |      /           ___---   ~~~~~~~~~~~~~~~~~+
//   |     /     __---   "plane" at psi = 35           |
//   +----+--'  (toe, the origin)        rock          |
//   |                                                 |
//   +-------------------------------------------------+ "rock_bottom"
//
// The block's own geometry sets the closed form: W its area x unit weight,
// A the length of the plane from the toe to the crack's foot,
// F = (c A + W cos(psi) tan(phi)) / (W sin(psi)).

DefineConstant[ lc = {1.0, Name "Parameters/element size"} ];
DefineConstant[ H = {20.0, Name "Parameters/slope height"} ];
DefineConstant[ face = {60.0, Name "Parameters/face angle (degrees)"} ];
DefineConstant[ psi = {35.0, Name "Parameters/sliding plane (degrees)"} ];
DefineConstant[ xc = {20.0, Name "Parameters/x of the tension crack"} ];

xcrest = H / Tan(face * Pi / 180);
yfoot = xc * Tan(psi * Pi / 180);
depth = 12.0;   // rock below the toe
left = 12.0;    // rock in front of the toe
right = 12.0;   // rock behind the crack

Point(1) = {0, 0, 0, lc};              // toe
Point(2) = {xcrest, H, 0, lc};         // crest
Point(3) = {xc, H, 0, lc};             // crack top
Point(4) = {xc, yfoot, 0, lc};         // crack foot
Point(5) = {xc + right, yfoot, 0, lc};
Point(6) = {xc + right, -depth, 0, lc};
Point(7) = {-left, -depth, 0, lc};
Point(8) = {-left, 0, 0, lc};

Line(1) = {1, 4};   // the sliding plane
Line(2) = {4, 3};   // the tension crack (free)
Line(3) = {3, 2};   // top of the block
Line(4) = {2, 1};   // the face
Line(5) = {4, 5};
Line(6) = {5, 6};
Line(7) = {6, 7};   // rock bottom
Line(8) = {7, 8};
Line(9) = {8, 1};

Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Curve Loop(2) = {-1, -9, -8, -7, -6, -5};
Plane Surface(2) = {2};

Physical Surface("block") = {1};
Physical Surface("rock") = {2};
Physical Curve("plane") = {1};
Physical Curve("rock_bottom") = {7};
Physical Curve("rock_sides") = {6, 8};
