// The quarter of a thick-walled cylinder (Lame): inner radius a = 10 mm, outer b = 20 mm,
// m quadrangles through the wall and n around the quarter (about square at mid-wall).
//   gmsh -2 -format msh41 lame.geo -setnumber m 20 -o lame_m20.msh
// Boundary groups: inner (r = a, the pressure), outer (r = b, free), xaxis (y = 0) and
// yaxis (x = 0), the two straight edges where the rollers act.
If (!Exists(m))
  m = 20;
EndIf
a = 0.01; b = 0.02;
n = Ceil(Pi / 2 * (a + b) / 2 / ((b - a) / m));
Point(1) = {0, 0, 0};
Point(2) = {a, 0, 0}; Point(3) = {b, 0, 0};
Point(4) = {0, b, 0}; Point(5) = {0, a, 0};
Line(1) = {2, 3};
Circle(2) = {3, 1, 4};
Line(3) = {4, 5};
Circle(4) = {5, 1, 2};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 3} = m + 1;
Transfinite Curve{2, 4} = n + 1;
Transfinite Surface{1};
Recombine Surface{1};
Physical Curve("xaxis") = {1};
Physical Curve("outer") = {2};
Physical Curve("yaxis") = {3};
Physical Curve("inner") = {4};
Physical Surface("wall") = {1};
