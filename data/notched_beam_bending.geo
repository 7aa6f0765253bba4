// Single-edge-notched beam in three-point bending: 200 mm x 50 mm, a slot 2 mm wide and a
// fifth of the depth (10 mm) deep at midspan, its tip a semicircle of radius 1 mm (a round
// tip keeps the stress at it finite, so the first onset converges under mesh refinement).
// Supports and loading pad are 10 mm flats: the pin centred 10 mm from the left end, the
// roller 10 mm from the right end (span 180 mm), the pad centred on the top at midspan.
// The beam is three surfaces on one mesh: the ends (x < 20 mm, x > 180 mm), which hold the
// supports, and the span between them ("beam").
L = 0.2;     // length (x)
H = 0.05;    // depth (y)
a = 0.01;    // notch depth
w = 0.002;   // notch width
r = w / 2;   // tip radius
e = 0.02;    // width of each end
s = 2.5e-3;  // element size away from the notch; the scene's mesh.element_size caps it
t = 1e-3;    // element size at the notch tip

Point(1) = {0, 0, 0, s};
Point(2) = {0.005, 0, 0, s};
Point(3) = {0.015, 0, 0, s};
Point(17) = {e, 0, 0, s};
Point(4) = {L / 2 - r, 0, 0, t};
Point(5) = {L / 2 - r, a - r, 0, t};
Point(6) = {L / 2, a - r, 0, t};  // centre of the tip
Point(7) = {L / 2, a, 0, t};      // the tip
Point(8) = {L / 2 + r, a - r, 0, t};
Point(9) = {L / 2 + r, 0, 0, t};
Point(18) = {L - e, 0, 0, s};
Point(10) = {L - 0.015, 0, 0, s};
Point(11) = {L - 0.005, 0, 0, s};
Point(12) = {L, 0, 0, s};
Point(13) = {L, H, 0, s};
Point(19) = {L - e, H, 0, s};
Point(14) = {L / 2 + 0.005, H, 0, s};
Point(15) = {L / 2 - 0.005, H, 0, s};
Point(20) = {e, H, 0, s};
Point(16) = {0, H, 0, s};

// The left end.
Line(1) = {1, 2};
Line(2) = {2, 3};  // pin
Line(3) = {3, 17};
Line(16) = {17, 20};  // left end | span
Line(15) = {20, 16};
Line(17) = {16, 1};
Curve Loop(1) = {1, 2, 3, 16, 15, 17};
Plane Surface(1) = {1};

// The span, with the notch and the pad.
Line(4) = {17, 4};
Line(5) = {4, 5};
Circle(6) = {5, 6, 7};
Circle(7) = {7, 6, 8};
Line(8) = {8, 9};
Line(9) = {9, 18};
Line(18) = {18, 19};  // span | right end
Line(12) = {19, 14};
Line(13) = {14, 15};  // loading pad
Line(14) = {15, 20};
Curve Loop(2) = {4, 5, 6, 7, 8, 9, 18, 12, 13, 14, -16};
Plane Surface(2) = {2};

// The right end.
Line(19) = {18, 10};
Line(20) = {10, 11};  // roller
Line(21) = {11, 12};
Line(22) = {12, 13};
Line(23) = {13, 19};
Curve Loop(3) = {19, 20, 21, 22, 23, -18};
Plane Surface(3) = {3};

Physical Surface("beam") = {2};
Physical Surface("ends") = {1, 3};
Physical Curve("pin") = {2};
Physical Curve("roller") = {20};
Physical Curve("pad") = {13};
