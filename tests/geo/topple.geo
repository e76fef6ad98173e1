// topple.geo -- a block of width b and height h standing on a wider base
// block, in contact along its foot "joint" (Goodman & Bray's block on an
// inclined plane: the model stays axis-aligned and the scene turns
// gravity by the plane's angle theta, so that x is down the plane).
//
//   y                  +-----+
//   |                  |     |  "block" b x h
//   |                  |     |
//   |        +---------+=====+---------+  "joint" (0..b at y = 0)
//   |        |        "base"            |
//   0--------+-------------------------+-- x    "base_bottom" held
//
// solid = 1 extrudes both along z by the width w (hexahedra): the joint
// is the surface 0 <= x <= b, y = 0.

DefineConstant[ b = {0.5, Name "Parameters/block width"} ];
DefineConstant[ h = {2.0, Name "Parameters/block height"} ];
DefineConstant[ w = {1.0, Name "Parameters/block width along z (solid)"} ];
DefineConstant[ solid = {0, Name "Parameters/extrude to 3D"} ];
DefineConstant[ n = {4, Name "Parameters/divisions across the block"} ];

m = b;        // base beyond the block on each side
hb = 0.5 * h; // base depth
nh = Ceil(n * h / b);

Point(1) = {-m, -hb, 0};
Point(2) = {b + m, -hb, 0};
Point(3) = {b + m, 0, 0};
Point(4) = {b, 0, 0};
Point(5) = {0, 0, 0};
Point(6) = {-m, 0, 0};
Point(7) = {b, h, 0};
Point(8) = {0, h, 0};

Line(1) = {1, 2};   // base bottom
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 5};   // the joint
Line(5) = {5, 6};
Line(6) = {6, 1};
Line(7) = {4, 7};
Line(8) = {7, 8};
Line(9) = {8, 5};

Curve Loop(1) = {1, 2, 3, 4, 5, 6};
Plane Surface(1) = {1};
Curve Loop(2) = {-4, 7, 8, 9};
Plane Surface(2) = {2};

Transfinite Curve{4, 8} = n + 1;
Transfinite Curve{7, 9} = nh + 1;
Transfinite Surface{2};
Recombine Surface{1, 2};

If (solid)
  base[] = Extrude {0, 0, w} { Surface{1}; Layers{2}; Recombine; };
  top[] = Extrude {0, 0, w} { Surface{2}; Layers{2}; Recombine; };
  Physical Volume("base") = {base[1]};
  Physical Volume("block") = {top[1]};
  // the lateral surfaces follow the curve loops: base[2] from line 1,
  // base[5] from line 4 (the joint); the block's extrusion of line -4 is
  // the same surface
  Physical Surface("joint") = {base[5]};
  Physical Surface("base_bottom") = {base[2]};
Else
  Physical Surface("base") = {1};
  Physical Surface("block") = {2};
  Physical Curve("joint") = {4};
  Physical Curve("base_bottom") = {1};
EndIf
