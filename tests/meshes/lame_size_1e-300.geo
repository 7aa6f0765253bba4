// Issue 28: data/verification/lame_cylinder.geo with s = 1e-300: 1e299 nodes on its curves
// (check grew to 2.7 GB in 90 s).
// Thick-walled cylinder (Lame): quarter of a ring with bore a = 0.1 m and outside b = 0.2 m.
a = 0.1;
b = 0.2;
s = 1e-300;   // the scene's mesh.element_size caps it

Point(1) = {0, 0, 0, s};
Point(2) = {a, 0, 0, s};
Point(3) = {b, 0, 0, s};
Point(4) = {0, b, 0, s};
Point(5) = {0, a, 0, s};
Line(1) = {2, 3};
Circle(2) = {3, 1, 4};
Line(3) = {4, 5};
Circle(4) = {5, 1, 2};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};

Physical Surface("ring") = {1};
Physical Curve("bottom") = {1};   // y = 0: symmetry, u_y = 0
Physical Curve("left") = {3};     // x = 0: symmetry, u_x = 0
Physical Curve("bore") = {4};
Physical Curve("outside") = {2};
Physical Point("bore_x") = {2};
