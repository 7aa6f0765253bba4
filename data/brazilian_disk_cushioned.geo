// Flattened Brazilian disk (R = 25 mm, 2 alpha = 20 deg) with a cushion bonded to each flat:
// a strip as wide as the flat and 1 mm thick, through which the platens press it. The rock
// and the cushions are conformal surfaces of one mesh (bonded). Points "top" and "bottom" are
// the middles of the cushions' outer faces, "top_platen" and "bottom_platen" those faces.
R = 0.025;
alpha = 10 * Pi / 180;
tc = 1e-3;     // cushion thickness
h = 1.25e-3;   // element size; the scene's mesh.element_size caps it
c = R * Cos(alpha);
s = R * Sin(alpha);

Point(1) = {0, 0, 0, h};   // centre
Point(2) = {s, c, 0, h};   // top flat: right end, middle, left end
Point(6) = {0, c, 0, h};
Point(3) = {-s, c, 0, h};
Point(4) = {-s, -c, 0, h};  // bottom flat: left end, middle, right end
Point(7) = {0, -c, 0, h};
Point(5) = {s, -c, 0, h};
Line(1) = {2, 6};
Line(2) = {6, 3};
Circle(3) = {3, 1, 4};  // left rim
Line(4) = {4, 7};
Line(5) = {7, 5};
Circle(6) = {5, 1, 2};  // right rim
Curve Loop(1) = {1, 2, 3, 4, 5, 6};
Plane Surface(1) = {1};

// The cushions.
Point(8) = {s, c + tc, 0, h};
Point(9) = {0, c + tc, 0, h};
Point(10) = {-s, c + tc, 0, h};
Line(7) = {2, 8};
Line(8) = {8, 9};
Line(9) = {9, 10};
Line(10) = {10, 3};
Curve Loop(2) = {7, 8, 9, 10, -2, -1};
Plane Surface(2) = {2};
Point(11) = {-s, -c - tc, 0, h};
Point(12) = {0, -c - tc, 0, h};
Point(13) = {s, -c - tc, 0, h};
Line(11) = {4, 11};
Line(12) = {11, 12};
Line(13) = {12, 13};
Line(14) = {13, 5};
Curve Loop(3) = {11, 12, 13, 14, -5, -4};
Plane Surface(3) = {3};

Physical Surface("rock") = {1};
Physical Surface("cushion") = {2, 3};
Physical Curve("top_platen") = {8, 9};
Physical Curve("bottom_platen") = {12, 13};
Physical Point("top") = {9};
Physical Point("bottom") = {12};
