// roller_wedge.geo -- a wedge of rock resting on a steep joint against a
// frictionless roller wall: the joint dips `dip` degrees down towards the
// wall and meets it at A = (L, a), so that the pair at A has both copies
// held in x (tests/roller_pairs.rs).
//
//   y = L  +---------------------+-------+
//          |                    /        |  "wedge": the triangle A, (L, L),
//          |      "ground"     /  wedge  |  (L - (L - a) / tan(dip), L)
//          |                  /          |
//          |                 / "joint"   |  "east": x = L, ux held (both
//          |                /            |  bodies' sides, A included)
//          |               /             |
//          |              /              |
//          |             +---------------+ A = (L, a)
//   y = 0  +-----------------------------+-- x
//          "west" x = 0, ux held;  "base" y = 0, ux, uy held
//
// solid = 1 extrudes both along z by w; "sides" (z = 0 and z = w) are then
// held in z as well.

DefineConstant[ dip = {65, Name "Parameters/joint dip (degrees)"} ];
DefineConstant[ lc = {1.0, Name "Parameters/element size"} ];
DefineConstant[ solid = {0, Name "Parameters/extrude to 3D"} ];
DefineConstant[ w = {2.0, Name "Parameters/width along z (solid)"} ];
L = 10;
a = 1;
xt = L - (L - a) / Tan(dip * Pi / 180);

Point(1) = {0, 0, 0, lc};
Point(2) = {L, 0, 0, lc};
Point(3) = {L, a, 0, lc};
Point(4) = {xt, L, 0, lc};
Point(5) = {0, L, 0, lc};
Point(6) = {L, L, 0, lc};

Line(1) = {1, 2};   // base
Line(2) = {2, 3};   // east, ground
Line(3) = {3, 4};   // the joint
Line(4) = {4, 5};   // top, ground
Line(5) = {5, 1};   // west
Line(6) = {3, 6};   // east, wedge
Line(7) = {6, 4};   // top, wedge

Curve Loop(1) = {1, 2, 3, 4, 5};
Plane Surface(1) = {1};
Curve Loop(2) = {6, 7, -3};
Plane Surface(2) = {2};

If (solid)
  g[] = Extrude {0, 0, w} { Surface{1}; Layers{2}; };
  k[] = Extrude {0, 0, w} { Surface{2}; Layers{2}; };
  Physical Volume("ground") = {g[1]};
  Physical Volume("wedge") = {k[1]};
  // lateral surfaces follow the curve loops: g[2 + i] from loop 1's i-th curve
  Physical Surface("joint") = {g[4]};
  Physical Surface("base") = {g[2]};
  Physical Surface("west") = {g[6]};
  Physical Surface("east") = {g[3], k[2]};
  Physical Surface("sides") = {1, 2, g[0], k[0]};
Else
  Physical Surface("ground") = {1};
  Physical Surface("wedge") = {2};
  Physical Curve("joint") = {3};
  Physical Curve("base") = {1};
  Physical Curve("west") = {5};
  Physical Curve("east") = {2, 6};
EndIf
