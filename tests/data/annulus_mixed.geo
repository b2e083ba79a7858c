// A quarter annulus (a = 10 mm, b = 20 mm): triangles in the inner half, quadrangles in the
// outer half, so both 2-D element types and a curved boundary meet one test.
// gmsh -2 -format msh41 annulus_mixed.geo
a = 0.01; b = 0.02; m = 0.015; h = 0.0015;
Point(1) = {0, 0, 0, h};
Point(2) = {a, 0, 0, h}; Point(3) = {m, 0, 0, h}; Point(4) = {b, 0, 0, h};
Point(5) = {0, a, 0, h}; Point(6) = {0, m, 0, h}; Point(7) = {0, b, 0, h};
Line(1) = {2, 3}; Line(2) = {3, 4};
Circle(3) = {4, 1, 7};
Line(4) = {7, 6}; Line(5) = {6, 5};
Circle(6) = {5, 1, 2};
Circle(7) = {3, 1, 6};
Curve Loop(1) = {1, 7, 5, 6};
Plane Surface(1) = {1};
Curve Loop(2) = {2, 3, 4, -7};
Plane Surface(2) = {2};
Transfinite Curve{2, 4} = 5;
Transfinite Curve{3, 7} = 12;
Transfinite Surface{2};
Recombine Surface{2};
Physical Curve("bottom") = {1, 2};
Physical Curve("outer") = {3};
Physical Curve("left") = {4, 5};
Physical Curve("inner") = {6};
Physical Surface("wall") = {1, 2};
