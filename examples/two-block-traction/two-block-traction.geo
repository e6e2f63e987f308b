// Traction patch test (docs/cases.md): the two-block patch with a pressure on the right
// sides. Two unit blocks of the same material, the upper one
// (slave) on the lower one (master), flat interface y = 0, non-matching meshes (8 slave
// edges over 11 master edges, unstructured triangles). Regenerate the .msh with
//   gmsh -2 -format msh41 two-block-traction.geo -o two-block-traction.msh
Geometry.AutoCoherence = 0;  // the two blocks touch but must not share points
Mesh.Algorithm = 6;          // Frontal-Delaunay
Mesh.Binary = 0;
lc1 = 1 / 8;
lc2 = 1 / 11;

// Upper block [0, 1] x [0, 1] (slave)
Point(1) = {0, 0, 0, lc1};
Point(2) = {1, 0, 0, lc1};
Point(3) = {1, 1, 0, lc1};
Point(4) = {0, 1, 0, lc1};
Line(1) = {1, 2};  // contact (slave)
Line(2) = {2, 3};
Line(3) = {3, 4};  // top
Line(4) = {4, 1};  // left
Transfinite Curve{1} = 9;
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};

// Lower block [0, 1] x [-1, 0] (master)
Point(5) = {0, -1, 0, lc2};
Point(6) = {1, -1, 0, lc2};
Point(7) = {1, 0, 0, lc2};
Point(8) = {0, 0, 0, lc2};
Line(5) = {5, 6};  // bottom
Line(6) = {6, 7};
Line(7) = {7, 8};  // contact (master)
Line(8) = {8, 5};  // left
Transfinite Curve{7} = 12;
Curve Loop(2) = {5, 6, 7, 8};
Plane Surface(2) = {2};

Physical Surface("upper_block") = {1};
Physical Surface("lower_block") = {2};
Physical Curve("upper_face") = {1};
Physical Curve("lower_face") = {7};
Physical Curve("top") = {3};
Physical Curve("bottom") = {5};
Physical Curve("rollers") = {4, 8};
Physical Curve("upper_right") = {2};
Physical Curve("lower_right") = {6};
