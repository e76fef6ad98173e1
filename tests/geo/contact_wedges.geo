// contact_wedges.geo -- two blocks of wedges in contact, for the contact
// patch tests of prisms (tests/contact3d.rs): a rectangular plan, cut into
// unstructured triangles, extruded in layers with Recombine, as layered
// ground is made.
//
// stacked = 1: the lower block extruded from the plan z = 0, the upper one
//   from the lower one's top: the joint z = h is a face of triangles (tri3,
//   tri6 at order 2).
//
//        z   +------------+   "top"  z = 2h
//        |   |   upper    |
//        h   +============+   "joint" (the lower block's top)
//            |   lower    |
//        0   +------------+-- x   "base" z = 0
//
// stacked = 0: the plan is two rectangles side by side, extruded together:
//   the joint x = w is a vertical face of quadrangles (quad4; quad8 for
//   prism15, quad9 for prism18).
//
//        y   +------+------+
//        |   | left | right|       "base" z = 0, "top" z = h,
//        l   |      |joint |       "x0" x = 0, "x1" x = 2w (stacked: x = w),
//            +------+------+-- x   "y0" y = 0, "y1" y = l
//            0      w     2w
//
// serendipity = 1 makes `gmsh -order 2` write prism15 instead of prism18.

DefineConstant[ stacked = {1, Name "Parameters/blocks stacked"} ];
DefineConstant[ lc = {0.4, Name "Parameters/triangle size"} ];
DefineConstant[ nz = {2, Name "Parameters/layers per block"} ];
DefineConstant[ serendipity = {0, Name "Parameters/serendipity"} ];
Mesh.SecondOrderIncomplete = serendipity;
w = 1.0;
l = 0.8;
h = 0.6;

Point(1) = {0, 0, 0, lc};
Point(2) = {w, 0, 0, lc};
Point(3) = {w, l, 0, lc};
Point(4) = {0, l, 0, lc};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};

If (stacked)
  // ex[0] the top, ex[1] the volume, ex[2..5] the sides swept by curves 1..4
  lower[] = Extrude {0, 0, h} { Surface{1}; Layers{nz}; Recombine; };
  upper[] = Extrude {0, 0, h} { Surface{lower[0]}; Layers{nz}; Recombine; };
  Physical Volume("lower") = {lower[1]};
  Physical Volume("upper") = {upper[1]};
  Physical Surface("joint") = {lower[0]};
  Physical Surface("top") = {upper[0]};
  Physical Surface("y0") = {lower[2], upper[2]};
  Physical Surface("x1") = {lower[3], upper[3]};
  Physical Surface("y1") = {lower[4], upper[4]};
  Physical Surface("x0") = {lower[5], upper[5]};
  Physical Surface("base") = {1};
Else
  Point(5) = {2 * w, 0, 0, lc};
  Point(6) = {2 * w, l, 0, lc};
  Line(5) = {2, 5};
  Line(6) = {5, 6};
  Line(7) = {6, 3};
  Curve Loop(2) = {5, 6, 7, -2};
  Plane Surface(2) = {2};
  left[] = Extrude {0, 0, h} { Surface{1}; Layers{nz}; Recombine; };
  right[] = Extrude {0, 0, h} { Surface{2}; Layers{nz}; Recombine; };
  // left[3] is swept by curve 2 (x = w), which right's curve loop also holds:
  // gmsh sweeps the shared curve once, so both volumes share that face
  Physical Volume("lower") = {left[1]};
  Physical Volume("upper") = {right[1]};
  Physical Surface("joint") = {left[3]};
  Physical Surface("top") = {left[0], right[0]};
  Physical Surface("y0") = {left[2], right[2]};
  Physical Surface("x1") = {right[3]};
  Physical Surface("y1") = {left[4], right[4]};
  Physical Surface("x0") = {left[5]};
  Physical Surface("base") = {1, 2};
EndIf
