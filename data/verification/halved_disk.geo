// The flattened disk of data/brazilian_disk_displacement.toml (R = 25 mm, 2 alpha = 20 deg,
// element size 1.25 mm) as two half-disks that share the loaded diameter x = 0: one continuum
// unless a scene's [[joint]] names the pair, which cuts the disk along that diameter (the
// crack of paper Fig. 11, made before loading). Each bottom half-flat has a midpoint for an
// x restraint of its own. tests/test_fracture_benchmarks.cpp, "HalvesCut...".
R = 0.025;
a = 10 * Pi / 180;
h = 1.25e-3;
c = R * Cos(a);
s = R * Sin(a);
Point(1) = {0, 0, 0, h};
Point(2) = {0, c, 0, h};
Point(3) = {s, c, 0, h};
Point(4) = {-s, c, 0, h};
Point(5) = {0, -c, 0, h};
Point(6) = {s, -c, 0, h};
Point(7) = {-s, -c, 0, h};
Point(8) = {R, 0, 0, h};
Point(9) = {-R, 0, 0, h};
Point(10) = {s / 2, -c, 0, h};
Point(11) = {-s / 2, -c, 0, h};
Line(1) = {2, 3};
Circle(2) = {3, 1, 8};
Circle(3) = {8, 1, 6};
Line(4) = {6, 10};
Line(14) = {10, 5};
Line(5) = {5, 2};
Line(6) = {4, 2};
Circle(7) = {9, 1, 4};
Circle(8) = {7, 1, 9};
Line(9) = {5, 11};
Line(19) = {11, 7};
Curve Loop(1) = {1, 2, 3, 4, 14, 5};
Plane Surface(1) = {1};
Curve Loop(2) = {6, -5, 9, 19, 8, 7};
Plane Surface(2) = {2};
Physical Surface("right") = {1};
Physical Surface("left") = {2};
Physical Curve("top_flat") = {1, 6};
Physical Curve("bottom_flat") = {4, 14, 9, 19};
Physical Point("bottom_right") = {10};
Physical Point("bottom_left") = {11};
Physical Point("bottom") = {5};
Physical Point("top") = {2};
