// Issue 28: data/verification/kirsch_plate.geo with point 6 moved to y = 2147483648: its
// 4 m size along 2e9 m of curve asks Gmsh for 1e9 nodes (check grew to 6.1 GB in 20 s).
// Plate with a circular hole (Kirsch): quarter model of a 80a x 80a plate with a hole of
// radius a = 1 at its centre, so the finite width changes the stress concentration by
// about +0.1 % (Heywood: (2 + (1 - d/W)^3) / (1 - d/W) = 3.002 for d/W = 0.025).
// tools/report rewrites the line "h = ...;" for each rung of its ladder: h is the element
// size on the hole, growing to s_far at the far corners.
a = 1.0;    // hole radius
W = 40.0;   // half-width of the plate
h = 0.1;    // element size on the hole
s_far = 4.0;

Point(1) = {0, 0, 0, h};          // centre of the hole (not meshed)
Point(2) = {a, 0, 0, h};
Point(3) = {0, a, 0, h};
Point(4) = {W, 0, 0, s_far};
Point(5) = {W, W, 0, s_far};
Point(6) = {0, 2147483648, 0, s_far};
Point(7) = {3 * a, 0, 0, 3 * h};  // keep the mesh fine near the hole along the axes
Point(8) = {0, 3 * a, 0, 3 * h};
Line(1) = {2, 7};
Line(2) = {7, 4};
Line(3) = {4, 5};
Line(4) = {5, 6};
Line(5) = {6, 8};
Line(6) = {8, 3};
Circle(7) = {3, 1, 2};
Curve Loop(1) = {1, 2, 3, 4, 5, 6, 7};
Plane Surface(1) = {1};

Physical Surface("plate") = {1};
Physical Curve("bottom") = {1, 2};   // y = 0: symmetry, u_y = 0
Physical Curve("left") = {5, 6};     // x = 0: symmetry, u_x = 0
Physical Curve("right") = {3};       // x = W: uniform tension
Physical Curve("hole") = {7};
