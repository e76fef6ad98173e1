// planar2d.geo -- a planar rock slope with a tension crack behind the
// crest, drawn as a rock engineer sketches Hoek & Bray's planar failure:
// a 30 m face at 60 degrees, a through-going sliding plane at 35 degrees
// daylighting at the toe, and a vertical tension crack 30 m behind the
// toe from the top of the slope down to the plane. The block in front of
// the crack and the rock around it are two bodies; the plane and the
// crack are their contacts (tests/corpus/planar2d.toml). Units: m.
//
//            crest       crack
//   y = 30     +-----------+---------------------+
//             /   block    |                     |
//            /        ..'''+                     |
//           /    ..'''  plane       ground       |
//   y = 0  +.''' (toe)                           |
//   -------+                                     |
//   |                                            |
//   +--------------------------------------------+  y = -20
DefineConstant[ lc = {1.5, Name "Parameters/element size"} ];
H = 30; face = 60 * Pi / 180; psi = 35 * Pi / 180;
xc = 30;                       // the crack, measured from the toe
yc = xc * Tan(psi);            // where the crack meets the plane
xf = H / Tan(face);            // the crest

// the block
Point(1) = {0, 0, 0, lc};
Point(2) = {xc, yc, 0, lc};
Point(3) = {xc, H, 0, lc};
Point(4) = {xf, H, 0, lc};
Line(1) = {1, 2};              // the sliding plane
Line(2) = {2, 3};              // the tension crack
Line(3) = {3, 4};
Line(4) = {4, 1};              // the face
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};

// the ground: below the plane, behind the crack, under the toe
Point(5) = {70, H, 0, 3 * lc};
Point(6) = {70, -20, 0, 4 * lc};
Point(7) = {-20, -20, 0, 4 * lc};
Point(8) = {-20, 0, 0, 2 * lc};
Line(5) = {3, 5};
Line(6) = {5, 6};
Line(7) = {6, 7};
Line(8) = {7, 8};
Line(9) = {8, 1};
Curve Loop(2) = {-1, -9, -8, -7, -6, -5, -2};
Plane Surface(2) = {2};

Physical Surface("block") = {1};
Physical Surface("ground") = {2};
Physical Curve("plane") = {1};
Physical Curve("crack") = {2};
Physical Curve("base") = {7};
Physical Curve("sides") = {6, 8};
