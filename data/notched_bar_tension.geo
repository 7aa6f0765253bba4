// Double-notched bar in tension (crack band check, issue 11): 60 mm x 20 mm with two
// semicircular notches of radius 5 mm at mid-length, leaving a 10 mm ligament. The notches
// are round so the stress at their roots is finite and the peak load converges under mesh
// refinement (a sharp notch's singular stress would make the first onset depend on h).
L = 0.06;   // length (x)
H = 0.02;   // height (y)
r = 0.005;  // notch radius
s = 5e-3;   // element size; the scene's mesh.element_size caps it

Point(1) = {0, 0, 0, s};
Point(2) = {L / 2 - r, 0, 0, s};
Point(3) = {L / 2, 0, 0, s};      // centre of the bottom notch
Point(4) = {L / 2, r, 0, s};      // root of the bottom notch
Point(5) = {L / 2 + r, 0, 0, s};
Point(6) = {L, 0, 0, s};
Point(7) = {L, H, 0, s};
Point(8) = {L / 2 + r, H, 0, s};
Point(9) = {L / 2, H, 0, s};      // centre of the top notch
Point(10) = {L / 2, H - r, 0, s}; // root of the top notch
Point(11) = {L / 2 - r, H, 0, s};
Point(12) = {0, H, 0, s};
Line(1) = {1, 2};
Circle(2) = {2, 3, 4};
Circle(3) = {4, 3, 5};
Line(4) = {5, 6};
Line(5) = {6, 7};
Line(6) = {7, 8};
Circle(7) = {8, 9, 10};
Circle(8) = {10, 9, 11};
Line(9) = {11, 12};
Line(10) = {12, 1};
Curve Loop(1) = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10};
Plane Surface(1) = {1};

Physical Surface("bar") = {1};
Physical Curve("left") = {10};
Physical Curve("right") = {5};
Physical Point("left_bottom") = {1};
