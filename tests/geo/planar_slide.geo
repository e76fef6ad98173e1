// planar_slide.geo -- a planar rock slope for tests/planar_slide.rs,
// written from the figures alone: H high, face at psi_f, a sliding plane
// "slide" at psi_p through the toe, a vertical tension crack z deep (its
// block face "crack_face", free, w wide) where the plane meets it. The
// block is held by the plane alone; the ground below and behind it is
// held at its base and sides. Units: m.
//
//          crest          crack
//   y = H   +--------------+  +------------------+
//          /     block     |  |                  |
//         /            ..''+..|      ground      |
//        /       ..''  slide                     |
//   toe +..''                                    |
//  -----+                                        |
//  ground (held: base, sides)                    |
//  ----------------------------------------------+

DefineConstant[ lc = {1.0, Name "Parameters/element size"} ];
DefineConstant[ H = {20.0, Name "Parameters/slope height"} ];
DefineConstant[ psi_f = {70.0, Name "Parameters/face angle (degrees)"} ];
DefineConstant[ psi_p = {35.0, Name "Parameters/sliding plane angle (degrees)"} ];
DefineConstant[ z = {6.0, Name "Parameters/tension crack depth"} ];
DefineConstant[ w = {0.4, Name "Parameters/tension crack width"} ];

d2r = Pi / 180;
xf = H / Tan(psi_f * d2r);          // the crest
xc = (H - z) / Tan(psi_p * d2r);    // the crack, where the plane meets it

// the block: toe, the crack's foot and top, the crest (counter-clockwise)
Point(1) = {0, 0, 0, lc};
Point(2) = {xc, H - z, 0, lc};
Point(3) = {xc, H, 0, lc};
Point(4) = {xf, H, 0, lc};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};

// the ground: under the plane, behind the crack, around the toe
Point(5) = {xc + w, H - z, 0, lc};
Point(6) = {xc + w, H, 0, lc};
Point(7) = {xc + w + 30, H, 0, 3 * lc};
Point(8) = {xc + w + 30, -20, 0, 4 * lc};
Point(9) = {-20, -20, 0, 4 * lc};
Point(10) = {-20, 0, 0, 2 * lc};
Line(5) = {2, 5};
Line(6) = {5, 6};
Line(7) = {6, 7};
Line(8) = {7, 8};
Line(9) = {8, 9};
Line(10) = {9, 10};
Line(11) = {10, 1};
// counter-clockwise: a clockwise loop gives every element a negative
// Jacobian, which the model refuses
Curve Loop(2) = {-10, -9, -8, -7, -6, -5, -1, -11};
Plane Surface(2) = {2};

Physical Surface("block") = {1};
Physical Surface("ground") = {2};
Physical Curve("slide") = {1};
Physical Curve("crack_face") = {2};
Physical Curve("base") = {9};
Physical Curve("sides") = {8, 10};
