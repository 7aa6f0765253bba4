// A unit square whose background size field asks for 1e-4 everywhere: 1.2e8 triangles that
// the point sizes do not show (Gmsh 4.8 does not evaluate fields through its API), but its
// curves' segments do once Gmsh has meshed them.
Point(1) = {0,0,0,0.1}; Point(2) = {1,0,0,0.1}; Point(3) = {1,1,0,0.1}; Point(4) = {0,1,0,0.1};
Line(1) = {1,2}; Line(2) = {2,3}; Line(3) = {3,4}; Line(4) = {4,1};
Curve Loop(1) = {1,2,3,4}; Plane Surface(1) = {1};
Field[1] = MathEval; Field[1].F = "1e-4"; Background Field = 1;
Physical Surface("rock") = {1};
