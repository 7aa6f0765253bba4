// Unit square, 2 x 2 structured cells: source of square_41.msh and square_22.msh
// (gmsh -2 square.geo -format msh41 -o square_41.msh; -format msh22 -o square_22.msh).
Point(1) = {0, 0, 0};
Point(2) = {1, 0, 0};
Point(3) = {1, 1, 0};
Point(4) = {0, 1, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve {1, 2, 3, 4} = 3;
Transfinite Surface {1};
Physical Surface("plate") = {1};
Physical Curve("bottom") = {1};
Physical Curve("top") = {3};
Physical Point("origin") = {1};
