SetFactory("OpenCASCADE");
// A rock slope: 20 m high face at 65 degrees on a 60 x 40 m section,
// jointed by two sets cut by the tool ([[joint_sets]] in the scene).
DefineConstant[ lc = {2.0, Name "Parameters/element size"} ];
H = 20; W = 60; D = 20; a = 65 * Pi / 180;
xt = 25; xf = xt + H / Tan(a);
Point(1) = {0, -D, 0, lc};
Point(2) = {W, -D, 0, lc};
Point(3) = {W, 0, 0, lc};
Point(4) = {xf, 0, 0, lc};
Point(5) = {xt, H, 0, lc};
Point(6) = {0, H, 0, lc};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 5};
Line(5) = {5, 6}; Line(6) = {6, 1};
Curve Loop(1) = {1, 2, 3, 4, 5, 6};
Plane Surface(1) = {1};
Physical Surface("rock") = {1};
Physical Curve("bottom") = {1};
Physical Curve("sides") = {2, 6};
