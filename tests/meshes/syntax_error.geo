// A missing closing brace on the second point.
Point(1) = {0, 0, 0};
Point(2) = {1, 0, 0;
Line(1) = {1, 2};
