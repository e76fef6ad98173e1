// footing_layers.geo -- a square concrete footing on two soil layers, the
// layered ground made as users make it: a triangulated plan extruded in
// layers (`Extrude {..} { Surface{..}; Layers{..}; Recombine; }`), so every
// cell is a prism (prism6, prism18 at order 2, prism15 with
// Mesh.SecondOrderIncomplete = 1). A column load on a small bearing plate
// near one corner of the footing, at (e, e) from its centre, lifts the
// opposite corner off the ground.
//
// Sample runs:
//   subcontact solve geo/footing_layers.toml           (e = 0.6 m, prism18)
//   setnumber = { e = 0.2 } in footing_layers.toml     (inside the kern: no lift)
//
//   plan (z = 0)                         section through the diagonal
//   y                                               plate (load)
//   |  +--------------------------+                   vvv
//   |  |          ground          |          +--------------+  z = t    footing
//   |  |     +------------+       |   -------+====base======+-------  z = 0
//   |  |     |  footing  []plate  |          layer1 (soft)             z = -h1
//   |  |     |     +      |       |   ---------------------------------
//   |  |     |   (0,0)    |       |          layer2 (stiffer)
//   |  |     +------------+       |   ---------------------------------  z = -h1 - h2
//   |  +--------------------------+                 bottom (held)
//   +------------------------------ x
//      W x W ground, B x B footing, the plate wp x wp centred at (e, e)
//
// Groups: volumes "footing", "layer1", "layer2" (layer1 and layer2 share
// their nodes: bonded); surfaces "base" (the footing's underside, shared
// with layer1: the contact), "plate" (the plate on the footing's top),
// "bottom" (z = -h1 - h2), "sides_x" (x = +-W/2), "sides_y" (y = +-W/2).
// The plan's triangles are of size lc under the footing, lc_far at the
// ground's edge; each layer is n1, n2 (the footing nf) prisms thick.

DefineConstant[
  lc     = {0.25, Min 0.02, Max 1, Name "Parameters/triangle size under the footing"},
  lc_far = {1.0, Min 0.1, Max 4, Name "Parameters/triangle size at the ground's edge"},
  e      = {0.6, Min 0, Max 0.8, Name "Parameters/eccentricity of the load along each axis"},
  n1     = {2, Min 1, Max 20, Name "Parameters/prisms through layer 1"},
  n2     = {3, Min 1, Max 30, Name "Parameters/prisms through layer 2"},
  nf     = {2, Min 1, Max 10, Name "Parameters/prisms through the footing"}
];
B  = 2.0;    // footing width (square)
t  = 0.5;    // footing thickness
W  = 8.0;    // ground width (square)
h1 = 1.0;    // layer 1 thickness
h2 = 3.0;    // layer 2 thickness
wp = 0.3;    // bearing plate width
eps = 1e-3;  // bounding-box margin for selecting surfaces and volumes

If (e + wp / 2 > B / 2)
  Error("footing_layers.geo: the plate (e = %g, width %g) must lie on the footing's top (e <= %g)", e, wp, B / 2 - wp / 2);
EndIf

// 1. The plan at z = 0: the ground around the footing, the footing's
//    underside around the plate, the plate.
Point(1) = {-W / 2, -W / 2, 0, lc_far};
Point(2) = { W / 2, -W / 2, 0, lc_far};
Point(3) = { W / 2,  W / 2, 0, lc_far};
Point(4) = {-W / 2,  W / 2, 0, lc_far};
Point(5) = {-B / 2, -B / 2, 0, lc};
Point(6) = { B / 2, -B / 2, 0, lc};
Point(7) = { B / 2,  B / 2, 0, lc};
Point(8) = {-B / 2,  B / 2, 0, lc};
Point(9)  = {e - wp / 2, e - wp / 2, 0, lc};
Point(10) = {e + wp / 2, e - wp / 2, 0, lc};
Point(11) = {e + wp / 2, e + wp / 2, 0, lc};
Point(12) = {e - wp / 2, e + wp / 2, 0, lc};
For i In {0:2}
  Line(4 * i + 1) = {4 * i + 1, 4 * i + 2};
  Line(4 * i + 2) = {4 * i + 2, 4 * i + 3};
  Line(4 * i + 3) = {4 * i + 3, 4 * i + 4};
  Line(4 * i + 4) = {4 * i + 4, 4 * i + 1};
  Curve Loop(i + 1) = {4 * i + 1, 4 * i + 2, 4 * i + 3, 4 * i + 4};
EndFor
Plane Surface(1) = {1, 2};   // the ground around the footing
Plane Surface(2) = {2, 3};   // the footing's underside around the plate
Plane Surface(3) = {3};      // under the plate

// 2. Extrusions: layer 1 down from the plan, layer 2 down from layer 1's
//    bottom, the footing up from its underside. Extruding the surfaces
//    together sweeps each shared curve once, so the volumes share faces.
Extrude {0, 0, -h1} { Surface{1, 2, 3}; Layers{n1}; Recombine; }
mid[] = Surface In BoundingBox{-W / 2 - eps, -W / 2 - eps, -h1 - eps, W / 2 + eps, W / 2 + eps, -h1 + eps};
Extrude {0, 0, -h2} { Surface{mid[]}; Layers{n2}; Recombine; }
Extrude {0, 0, t} { Surface{2, 3}; Layers{nf}; Recombine; }

// 3. Groups, selected by where they lie.
Physical Volume("footing") = Volume In BoundingBox{-B / 2 - eps, -B / 2 - eps, -eps, B / 2 + eps, B / 2 + eps, t + eps};
Physical Volume("layer1") = Volume In BoundingBox{-W / 2 - eps, -W / 2 - eps, -h1 - eps, W / 2 + eps, W / 2 + eps, eps};
Physical Volume("layer2") = Volume In BoundingBox{-W / 2 - eps, -W / 2 - eps, -h1 - h2 - eps, W / 2 + eps, W / 2 + eps, -h1 + eps};
Physical Surface("base") = {2, 3};
Physical Surface("plate") = Surface In BoundingBox{e - wp / 2 - eps, e - wp / 2 - eps, t - eps, e + wp / 2 + eps, e + wp / 2 + eps, t + eps};
Physical Surface("bottom") = Surface In BoundingBox{-W / 2 - eps, -W / 2 - eps, -h1 - h2 - eps, W / 2 + eps, W / 2 + eps, -h1 - h2 + eps};
Physical Surface("sides_x") = Surface In BoundingBox{-W / 2 - eps, -W / 2 - eps, -h1 - h2 - eps, -W / 2 + eps, W / 2 + eps, eps};
Physical Surface("sides_x") += Surface In BoundingBox{W / 2 - eps, -W / 2 - eps, -h1 - h2 - eps, W / 2 + eps, W / 2 + eps, eps};
Physical Surface("sides_y") = Surface In BoundingBox{-W / 2 - eps, -W / 2 - eps, -h1 - h2 - eps, W / 2 + eps, -W / 2 + eps, eps};
Physical Surface("sides_y") += Surface In BoundingBox{-W / 2 - eps, W / 2 - eps, -h1 - h2 - eps, W / 2 + eps, W / 2 + eps, eps};
