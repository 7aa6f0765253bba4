// Issue 28: data/verification/hondros_disk.geo with s = 1e-9: 1.6e8 nodes on its arcs
// (check grew to 1.8 GB in 30 s).
// Brazilian disk loaded by uniform radial pressure on two opposite arcs (Hondros 1959): a
// disk of radius R = 25 mm, the arcs spanning 2 alpha = 20 deg about the loaded (vertical)
// diameter, with a node at the centre. The scene's mesh.element_size caps the size.
R = 0.025;
alpha = 10 * Pi / 180;
s = 1e-9;

Point(1) = {0, 0, 0, s};                                   // centre
Point(2) = {R * Sin(alpha), R * Cos(alpha), 0, s};         // top arc, right end
Point(3) = {0, R, 0, s};                                   // top
Point(4) = {-R * Sin(alpha), R * Cos(alpha), 0, s};        // top arc, left end
Point(5) = {-R * Sin(alpha), -R * Cos(alpha), 0, s};       // bottom arc, left end
Point(6) = {0, -R, 0, s};                                  // bottom
Point(7) = {R * Sin(alpha), -R * Cos(alpha), 0, s};        // bottom arc, right end
Circle(1) = {2, 1, 3};
Circle(2) = {3, 1, 4};
Circle(3) = {4, 1, 5};
Circle(4) = {5, 1, 6};
Circle(5) = {6, 1, 7};
Circle(6) = {7, 1, 2};
Curve Loop(1) = {1, 2, 3, 4, 5, 6};
Plane Surface(1) = {1};
Point{1} In Surface{1};

Physical Surface("body") = {1};
Physical Curve("top_arc") = {1, 2};
Physical Curve("bottom_arc") = {4, 5};
Physical Curve("rim") = {3, 6};
Physical Point("center") = {1};
Physical Point("top") = {3};
