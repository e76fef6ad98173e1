// slope2d.geo -- a 20 m rock cut at 65 degrees above a 10 m bench, the face
// looking west (-x). The bedding and cross joints are cut by the tool
// ([[joint_sets]] in slope2d.toml); this file holds only the rock.
SetFactory("OpenCASCADE");
DefineConstant[ lc = {2.0, Name "Parameters/element size"} ];
H = 20; a = 65 * Pi / 180;
xt = 20; xc = xt + H / Tan(a);
Point(1) = {0, 0, 0, lc};
Point(2) = {70, 0, 0, lc};
Point(3) = {70, 10 + H, 0, lc};
Point(4) = {xc, 10 + H, 0, lc};
Point(5) = {xt, 10, 0, lc};
Point(6) = {0, 10, 0, lc};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4};
Line(4) = {4, 5}; Line(5) = {5, 6}; Line(6) = {6, 1};
Curve Loop(1) = {1, 2, 3, 4, 5, 6};
Plane Surface(1) = {1};
Physical Surface("rock") = {1};
Physical Curve("base") = {1};
Physical Curve("east") = {2};
Physical Curve("west") = {6};
Physical Curve("face") = {4};
