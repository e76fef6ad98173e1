// dam3d.geo -- a 40 m gravity dam of two monoliths on a rock foundation,
// as a dam engineer models one: the section of tests/corpus/dam2d.geo
// (vertical upstream face at x = 0, base 30 m, crest 5 m, a lift joint at
// z = 15 m) extruded 24 m along the axis (y) and cut at y = 12 m by a
// transverse contraction joint, so the lift joint crosses it. The
// foundation's joints are cut by the tool ([[joint_sets]] in the scene);
// the base, the lift joint and the contraction joint are groups of their
// own. OpenCASCADE volumes joined by BooleanFragments.
//
// Groups: "a_lower", "a_upper" (the monolith at y 0..12, its two lifts),
// "b_lower", "b_upper" (y 12..24), "foundation"; "base" (dam on rock),
// "lift_joint" (z = 15), "contraction" (y = 12); "upstream_face" (x = 0,
// the dam), "reservoir_floor" (the rock's top upstream, x < 0),
// "bottom" (z = -30), "ends" (x = -35 and 65), "sides" (y = 0 and 24, the
// rock only: the dam's ends are free).
SetFactory("OpenCASCADE");
DefineConstant[ lc = {3.0, Name "Parameters/element size in the dam"} ];
DefineConstant[ lc_far = {8.0, Name "Parameters/element size far in the rock"} ];
H = 40; B = 30; bc = 5; hl = 15;   // height, base, crest, lift joint
L = 24; yc = 12;                   // the dam's length, the contraction joint
X0 = -35; X1 = 65; D = 30;         // the rock
xl = B - (B - bc) * hl / H;        // the downstream face at the lift joint

// the two lifts' sections in the plane y = 0
Point(1) = {0, 0, 0}; Point(2) = {B, 0, 0}; Point(3) = {xl, 0, hl}; Point(4) = {0, 0, hl};
Point(5) = {bc, 0, H}; Point(6) = {0, 0, H};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Line(5) = {3, 5}; Line(6) = {5, 6}; Line(7) = {6, 4};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Curve Loop(2) = {-3, 5, 6, 7}; Plane Surface(2) = {2};
// each lift of each monolith a volume of its own
a_lower[] = Extrude {0, yc, 0} { Surface{1}; };
a_upper[] = Extrude {0, yc, 0} { Surface{2}; };
moved[] = Translate {0, yc, 0} { Duplicata { Surface{1, 2}; } };
b_lower[] = Extrude {0, L - yc, 0} { Surface{moved[0]}; };
b_upper[] = Extrude {0, L - yc, 0} { Surface{moved[1]}; };
Box(100) = {X0, 0, -D, X1 - X0, L, D};
BooleanFragments{ Volume{a_lower[1], a_upper[1], b_lower[1], b_upper[1], 100}; Delete; }{}

e = 1e-3;
Physical Volume("a_lower") = Volume In BoundingBox{-e, -e, -e, B + e, yc + e, hl + e};
Physical Volume("a_upper") = Volume In BoundingBox{-e, -e, hl - e, xl + e, yc + e, H + e};
Physical Volume("b_lower") = Volume In BoundingBox{-e, yc - e, -e, B + e, L + e, hl + e};
Physical Volume("b_upper") = Volume In BoundingBox{-e, yc - e, hl - e, xl + e, L + e, H + e};
Physical Volume("foundation") = Volume In BoundingBox{X0 - e, -e, -D - e, X1 + e, L + e, e};
Physical Surface("base") = Surface In BoundingBox{-e, -e, -e, B + e, L + e, e};
Physical Surface("lift_joint") = Surface In BoundingBox{-e, -e, hl - e, xl + e, L + e, hl + e};
Physical Surface("contraction") = Surface In BoundingBox{-e, yc - e, -e, B + e, yc + e, H + e};
Physical Surface("upstream_face") = Surface In BoundingBox{-e, -e, -e, e, L + e, H + e};
Physical Surface("reservoir_floor") = Surface In BoundingBox{X0 - e, -e, -e, e, L + e, e};
Physical Surface("bottom") = Surface In BoundingBox{X0 - e, -e, -D - e, X1 + e, L + e, -D + e};
Physical Surface("ends") = Surface In BoundingBox{X0 - e, -e, -D - e, X0 + e, L + e, e};
Physical Surface("ends") += Surface In BoundingBox{X1 - e, -e, -D - e, X1 + e, L + e, e};
Physical Surface("sides") = Surface In BoundingBox{X0 - e, -e, -D - e, X1 + e, e, e};
Physical Surface("sides") += Surface In BoundingBox{X0 - e, L - e, -D - e, X1 + e, L + e, e};
MeshSize{ PointsOf{ Volume{:}; } } = lc_far;
MeshSize{ PointsOf{ Volume{a_lower[1], a_upper[1], b_lower[1], b_upper[1]}; } } = lc;
