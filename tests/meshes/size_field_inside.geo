// A unit square whose background field asks for 1e-6 at its centre, growing as 0.2 r^2 to its
// boundary: about 3.6e7 triangles (the integral of 1 / (0.433 h^2) over the square) that
// neither the point sizes nor the curves' segments show (0.05 to 0.1); the meshing process's
// time and memory limits stop it.
Point(1) = {0,0,0,0.1}; Point(2) = {1,0,0,0.1}; Point(3) = {1,1,0,0.1}; Point(4) = {0,1,0,0.1};
Line(1) = {1,2}; Line(2) = {2,3}; Line(3) = {3,4}; Line(4) = {4,1};
Curve Loop(1) = {1,2,3,4}; Plane Surface(1) = {1};
Field[1] = MathEval; Field[1].F = "1e-6 + 0.2 * ((x - 0.5)^2 + (y - 0.5)^2)";
Background Field = 1;
Physical Surface("rock") = {1};
