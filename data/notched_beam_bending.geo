// Single-edge-notched beam in three-point bending: 200 mm x 50 mm, a slot 2 mm wide and a
// fifth of the depth (10 mm) deep at midspan, its tip a semicircle of radius 1 mm (a round
// tip keeps the stress at it finite, so the first onset converges under mesh refinement).
// Supports and loading pad are 10 mm flats: the pin centred 10 mm from the left end, the
// roller 10 mm from the right end (span 180 mm), the pad centred on the top at midspan.
L = 0.2;     // length (x)
H = 0.05;    // depth (y)
a = 0.01;    // notch depth
w = 0.002;   // notch width
r = w / 2;   // tip radius
s = 2.5e-3;  // element size away from the notch; the scene's mesh.element_size caps it
t = 1e-3;    // element size at the notch tip

Point(1) = {0, 0, 0, s};
Point(2) = {0.005, 0, 0, s};
Point(3) = {0.015, 0, 0, s};
Point(4) = {L / 2 - r, 0, 0, t};
Point(5) = {L / 2 - r, a - r, 0, t};
Point(6) = {L / 2, a - r, 0, t};  // centre of the tip
Point(7) = {L / 2, a, 0, t};      // the tip
Point(8) = {L / 2 + r, a - r, 0, t};
Point(9) = {L / 2 + r, 0, 0, t};
Point(10) = {L - 0.015, 0, 0, s};
Point(11) = {L - 0.005, 0, 0, s};
Point(12) = {L, 0, 0, s};
Point(13) = {L, H, 0, s};
Point(14) = {L / 2 + 0.005, H, 0, s};
Point(15) = {L / 2 - 0.005, H, 0, s};
Point(16) = {0, H, 0, s};
Line(1) = {1, 2};
Line(2) = {2, 3};  // pin
Line(3) = {3, 4};
Line(4) = {4, 5};
Circle(5) = {5, 6, 7};
Circle(6) = {7, 6, 8};
Line(7) = {8, 9};
Line(8) = {9, 10};
Line(9) = {10, 11};  // roller
Line(10) = {11, 12};
Line(11) = {12, 13};
Line(12) = {13, 14};
Line(13) = {14, 15};  // loading pad
Line(14) = {15, 16};
Line(15) = {16, 1};
Curve Loop(1) = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15};
Plane Surface(1) = {1};

Physical Surface("beam") = {1};
Physical Curve("pin") = {2};
Physical Curve("roller") = {9};
Physical Curve("pad") = {13};
