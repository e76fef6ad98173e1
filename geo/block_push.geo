// block_push.geo -- a block pushed across a base under displacement control:
// the block's left side is moved 1 mm to the right while a pressure presses
// it down; with cohesion 0 every pair of the joint slips and carries the
// Coulomb shear f |sigma_n|.
//
// Sample run:
//   subcontact solve geo/block_push.toml
//
//            top (pressure)
//          +-----------+
//   push ->|   block   |
//          +===joint===+
//   +-------------------------+
//   |          base           |
//   +-------------------------+
//              bottom (held)

DefineConstant[ lc = {0.1, Min 0.005, Max 1, Name "Parameters/element size"} ];
Point(1) = {0, 0, 0};
Point(2) = {2, 0, 0};
Point(3) = {2, 0.5, 0};
Point(4) = {1.5, 0.5, 0};
Point(5) = {0.5, 0.5, 0};
Point(6) = {0, 0.5, 0};
Point(7) = {1.5, 1.0, 0};
Point(8) = {0.5, 1.0, 0};

Line(1) = {1, 2};
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

n = Ceil(1.0 / lc) + 1;
Transfinite Curve{4, 8} = n;
Transfinite Curve{7, 9} = Ceil(0.5 / lc) + 1;
Transfinite Surface{2};
Recombine Surface{1, 2};
Mesh.CharacteristicLengthMax = lc;

Physical Surface("base") = {1};
Physical Surface("block") = {2};
Physical Curve("joint") = {4};
Physical Curve("bottom") = {1};
Physical Curve("top") = {8};
Physical Curve("push") = {9};
