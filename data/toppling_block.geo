// A block on a 20-degree slope (rockdd issue 30): width 0.4 m, height 1.6 m, its base on the
// slope face. tan(20 deg) = 0.364 against b / h = 0.250: it topples (b / h < tan).
// The joint's friction (40 deg) keeps it from sliding.
sb = 0.25;  // element size in the slope
sk = 0.1;   // element size in the block
Point(1) = {0, 0, 0, sb};
Point(2) = {6.0, 0, 0, sb};
Point(3) = {6.0, 0.816178594402786, 0, sb};
Point(4) = {0, 3.0, 0, sb};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Point(11) = {1.5, 2.4540446486006964, 0, sk};
Point(12) = {1.8758770483143634, 2.317236591270429, 0, sk};
Point(13) = {2.4231092776354335, 3.8207447845278826, 0, sk};
Point(14) = {2.04723222932107, 3.95755284185815, 0, sk};
Line(11) = {11, 12};
Line(12) = {12, 13};
Line(13) = {13, 14};
Line(14) = {14, 11};
Curve Loop(11) = {11, 12, 13, 14};
Plane Surface(11) = {11};
Physical Surface("slope") = {1};
Physical Surface("block") = {11};
Physical Curve("slope_bottom") = {1};
