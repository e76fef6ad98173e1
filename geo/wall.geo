// wall.geo -- a gravity wall of width B and height Hw standing on rock, in
// contact along its "base"; a horizontal load on its "back" face pushes it
// towards its toe (x = B): it slides on its base or tips about its toe.
//
//   y
//   |        +-----+
//   | "back" |     |  "wall" B x Hw
//   |  -->   |     |
//   |  -->   |     |
//   +----+---+=====+---+------ "base" (0 <= x <= B, y = 0)
//   |    |   "rock"        |  "rock_sides" held in x
//   +--------------------------+ "rock_bottom" held
//   -m                      B + m

DefineConstant[ B = {2.0, Name "Parameters/wall width"} ];
DefineConstant[ Hw = {4.0, Name "Parameters/wall height"} ];
DefineConstant[ n = {6, Name "Parameters/divisions across the wall"} ];

m = B;          // rock beyond the wall on each side
d = B;          // rock depth
nh = Ceil(n * Hw / B);

Point(1) = {-m, -d, 0};
Point(2) = {B + m, -d, 0};
Point(3) = {B + m, 0, 0};
Point(4) = {B, 0, 0};
Point(5) = {0, 0, 0};
Point(6) = {-m, 0, 0};
Point(7) = {B, Hw, 0};
Point(8) = {0, Hw, 0};

Line(1) = {1, 2};   // rock bottom
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 5};   // the base
Line(5) = {5, 6};
Line(6) = {6, 1};
Line(7) = {4, 7};   // the toe's face
Line(8) = {7, 8};
Line(9) = {8, 5};   // the back

Curve Loop(1) = {1, 2, 3, 4, 5, 6};
Plane Surface(1) = {1};
Curve Loop(2) = {-4, 7, 8, 9};
Plane Surface(2) = {2};

Transfinite Curve{4, 8} = n + 1;
Transfinite Curve{7, 9} = nh + 1;
Transfinite Surface{2};
Recombine Surface{1, 2};

Physical Surface("rock") = {1};
Physical Surface("wall") = {2};
Physical Curve("base") = {4};
Physical Curve("back") = {9};
Physical Curve("rock_bottom") = {1};
Physical Curve("rock_sides") = {2, 6};
