// cgs4.geo -- a block on an inclined plane pushed up the slope (after the
// NAFEMS contact benchmark CGS-4): a block of weight G rests on a plane
// inclined at alpha, tan(alpha) = 0.1, friction f = 0.3, no cohesion, and a
// horizontal force F pushes it up the slope. A rigid block slips when
//
//     F / G = (tan(alpha) + f) / (1 - f tan(alpha)) = 0.4 / 0.97 = 0.412371
//
// (along the slope F cos(alpha) - G sin(alpha) = f N, across it
// N = F sin(alpha) + G cos(alpha)). cgs4.toml holds G at every load step and
// ramps F to 0.995 of that limit: the block holds while its joint slips
// from the corners inwards (at 0.995 only 3 of 21 pairs, in the middle,
// stick); at 1.005 of it the run stops with "loss of equilibrium". The
// elastic model finds the rigid-block limit whatever the block's stiffness:
// slipping pairs carry f |sigma_n|, so gross slip comes when f N is used up.
//
// Sample runs:
//   subcontact solve geo/cgs4.toml                     (quad9, lc = 0.1)
//   subcontact solve geo/cgs4.toml --out /tmp/cgs4     (results elsewhere)
//   setnumber = { lc = 0.05 } in cgs4.toml             (a finer mesh; the limit does not move)
//
//   drawn along the slope (the model is then turned by alpha about the origin):
//
//                  top          G: the block's weight, vertical (global -y)
//              +---------+
//   F -->  push|  block  |      F: horizontal (global +x), up the slope
//              +==joint==+
//   +-----------------------------+
//   |            base             |
//   +-----------------------------+
//              bottom (held)
//
// The block is L = 1 long and h thick (G = 1 for h = 0.25 with the
// density and gravity of cgs4.toml; G and F = traction x h both scale with
// h, so F / G does not); the base is
// B = 3 long and H = 0.5 thick, the block in its middle. Groups: base,
// block (surfaces); joint (the contact), bottom (held), push (the block's
// downhill side, where F acts), top (the block's upper face).

DefineConstant[ lc = {0.1, Min 0.005, Max 1, Name "Parameters/element size"} ];
DefineConstant[ h = {0.25, Min 0.01, Max 2, Name "Parameters/block thickness"} ];
DefineConstant[ quad = {1, Name "Parameters/quadrilaterals"} ];

// 1. Geometry along the slope.
alpha = Atan(0.1);
L = 1.0;
B = 3.0;
H = 0.5;
s0 = (B - L) / 2;

Point(1) = {0, -H, 0};
Point(2) = {B, -H, 0};
Point(3) = {B, 0, 0};
Point(4) = {s0 + L, 0, 0};
Point(5) = {s0, 0, 0};
Point(6) = {0, 0, 0};
Point(7) = {s0 + L, h, 0};
Point(8) = {s0, h, 0};

Line(1) = {1, 2};   // bottom
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 5};   // the joint
Line(5) = {5, 6};
Line(6) = {6, 1};
Line(7) = {4, 7};
Line(8) = {7, 8};   // top
Line(9) = {8, 5};   // push

Curve Loop(1) = {1, 2, 3, 4, 5, 6};
Plane Surface(1) = {1};
Curve Loop(2) = {-4, 7, 8, 9};
Plane Surface(2) = {2};

// 2. Mesh: a structured block, an unstructured base meeting it node to node.
Transfinite Curve{4, 8} = Ceil(L / lc) + 1;
Transfinite Curve{7, 9} = Ceil(h / lc) + 1;
Transfinite Surface{2};
If (quad)
  Recombine Surface{1, 2};
EndIf
Mesh.CharacteristicLengthMax = lc;

// 3. Onto the slope.
Rotate {{0, 0, 1}, {0, 0, 0}, alpha} { Surface{1, 2}; }

Physical Surface("base") = {1};
Physical Surface("block") = {2};
Physical Curve("joint") = {4};
Physical Curve("bottom") = {1};
Physical Curve("push") = {9};
Physical Curve("top") = {8};
