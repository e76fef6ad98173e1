// seat.geo -- a half-disc block of radius R resting in a semicircular
// cradle cut into a ground block: contact "seat" on the arc (faceted,
// facets of unequal length: mesh sizes differ at the arc's points).
DefineConstant[ R = {1.0, Name "Parameters/radius"} ];
DefineConstant[ lc = {0.12, Name "Parameters/mesh size"} ];
Point(1) = {0, 0, 0, lc};
Point(2) = {-R, 0, 0, lc};
Point(3) = {0, -R, 0, 1.4 * lc};
Point(4) = {R, 0, 0, 0.8 * lc};
Point(5) = {2 * R, 0, 0, 2 * lc};
Point(6) = {2 * R, -2 * R, 0, 2 * lc};
Point(7) = {-2 * R, -2 * R, 0, 2 * lc};
Point(8) = {-2 * R, 0, 0, 2 * lc};
Circle(1) = {2, 1, 3};
Circle(2) = {3, 1, 4};
Line(3) = {4, 2};
Line(4) = {4, 5};
Line(5) = {5, 6};
Line(6) = {6, 7};
Line(7) = {7, 8};
Line(8) = {8, 2};
Curve Loop(1) = {1, 2, 3};
Plane Surface(1) = {1};
Curve Loop(2) = {-2, -1, -8, -7, -6, -5, -4};
Plane Surface(2) = {2};
Physical Surface("block") = {1};
Physical Surface("ground") = {2};
Physical Curve("seat") = {1, 2};
Physical Curve("ground_bottom") = {6};
