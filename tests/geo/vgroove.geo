// vgroove.geo -- a wedge in a V-groove: the rock block [-2, 2] x [0, L] x
// [-1, 1] with a groove of faces dipping 45 degrees towards each other
// (their crease along the y axis at z = 0, their top edges at x = +-1,
// z = 1), and the wedge that fills it, its top flush with the rock's.
// "groove" is one physical surface holding both faces: one contact group
// on two planes.
//
//      z   wedge "top"
//    1 +--+---------+--+
//      |   \ wedge /   |   rock: "bottom" (z = -1), "ends" (y = 0, L);
//      |    \     /    |   wedge: "wedge_ends" (y = 0, L)
//    0 +     \   /     +-- x
//      |      \ /      |
//   -1 +-------+-------+
//     -2       0       2

SetFactory("OpenCASCADE");
DefineConstant[ lc = {0.2, Name "Parameters/element size"} ];
L = 2.0; half = 1.0; depth = 1.0;
Point(1) = {-half, 0, depth, lc}; Point(2) = {0, 0, 0, lc}; Point(3) = {half, 0, depth, lc};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 1};
Curve Loop(1) = {1, 2, 3};
Plane Surface(1) = {1};
w[] = Extrude {0, L, 0} { Surface{1}; };
Box(10) = {-2 * half, 0, -1, 4 * half, L, depth + 1};
r() = BooleanDifference{ Volume{10}; Delete; }{ Volume{w[1]}; };
all() = BooleanFragments{ Volume{r(), w[1]}; Delete; }{};
e = 1e-3;
wedge() = Volume In BoundingBox{-half - e, -e, -e, half + e, L + e, depth + e};
rk() = all(); rk() -= wedge();
Physical Volume("rock") = {rk()};
Physical Volume("wedge") = {wedge()};
Physical Surface("groove") = {Surface In BoundingBox{-half - e, -e, -e, e, L + e, depth + e}, Surface In BoundingBox{-e, -e, -e, half + e, L + e, depth + e}};
Physical Surface("bottom") = {Surface In BoundingBox{-2 * half - e, -e, -1 - e, 2 * half + e, L + e, -1 + e}};
ends() = {Surface In BoundingBox{-2 * half - e, -e, -1 - e, 2 * half + e, e, depth + e}, Surface In BoundingBox{-2 * half - e, L - e, -1 - e, 2 * half + e, L + e, depth + e}};
wends() = {Surface In BoundingBox{-half - e, -e, -e, half + e, e, depth + e}, Surface In BoundingBox{-half - e, L - e, -e, half + e, L + e, depth + e}};
rends() = ends(); rends() -= wends();
Physical Surface("ends") = {rends()};
Physical Surface("wedge_ends") = {wends()};
Physical Surface("top") = {Surface In BoundingBox{-half - e, -e, depth - e, half + e, L + e, depth + e}};
Mesh.CharacteristicLengthMax = lc;
