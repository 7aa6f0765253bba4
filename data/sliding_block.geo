// Paper benchmark 2 (section 3.2): block II slides down the 30-degree face of block I.
// Two separately meshed triangles, so two blocks; their contact is the scene's [[joint]].
H = 5.773502691896257;   // 10 tan(30 deg): the slope runs from (0, H) down to (10, 0)
s1 = 0.5;   // element size in block I
s2 = 0.25;  // element size in block II

Point(1) = {0, 0, 0, s1};
Point(2) = {10, 0, 0, s1};
Point(3) = {0, H, 0, s1};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 1};
Curve Loop(1) = {1, 2, 3};
Plane Surface(1) = {1};

// Block II: its hypotenuse lies on the slope between x = 0.5 and x = 1.5, its top is level.
t = 0.5773502691896257;
Point(11) = {0.5, H - 0.5 * t, 0, s2};
Point(12) = {1.5, H - 1.5 * t, 0, s2};
Point(13) = {1.5, H - 0.5 * t, 0, s2};
Line(11) = {11, 12};
Line(12) = {12, 13};
Line(13) = {13, 11};
Curve Loop(11) = {11, 12, 13};
Plane Surface(11) = {11};

Physical Surface("block1") = {1};
Physical Surface("block2") = {11};
Physical Curve("block1_bottom") = {1};
Physical Curve("block1_left") = {3};
