// Tiny geometry for the scene-reader tests (tests/scenes/good/full.toml): a 0.04 m x 0.01 m
// beam "rock" with curves "left" and "top" and the point "tip", and two triangular blocks
// "block1" and "block2" meeting on a 30 degree interface above it.
lc = 0.005;
Point(1) = {0, 0, 0, lc};
Point(2) = {0.04, 0, 0, lc};
Point(3) = {0.04, 0.01, 0, lc};
Point(4) = {0, 0.01, 0, lc};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};

// Blocks: block1 below the inclined face, block2 resting on it (separately meshed).
Point(5) = {0, 0.02, 0, lc};
Point(6) = {0.04, 0.02, 0, lc};
Point(7) = {0, 0.02 + 0.04 * Tan(Pi / 6), 0, lc};
Line(5) = {5, 6};
Line(6) = {6, 7};
Line(7) = {7, 5};
Curve Loop(2) = {5, 6, 7};
Plane Surface(2) = {2};
Point(8) = {0.04, 0.02 + 0.04 * Tan(Pi / 6), 0, lc};
Line(8) = {6, 8};
Line(9) = {8, 7};
Curve Loop(3) = {-6, 8, 9};
Plane Surface(3) = {3};

Physical Surface("rock") = {1};
Physical Surface("block1") = {2};
Physical Surface("block2") = {3};
Physical Curve("left") = {4};
Physical Curve("top") = {3};
Physical Point("tip") = {2};
