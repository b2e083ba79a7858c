// The quarter plate with a hole (plate_hole.yaml) as a body-fitted mesh: a 50 mm square minus a
// disc of R = 5 mm at the origin, unstructured first-order quadrangles of size h
// everywhere (uniform, like the lattice; a constant horizon needs it).
//   gmsh -2 -format msh41 plate_hole.geo -setnumber h 0.0005 -o plate_hole_h05.msh
// Boundary groups: left (x = 0), bottom (y = 0), right (x = 50 mm, the traction), top, hole.
If (!Exists(h))
  h = 0.001;
EndIf
L = 0.05; R = 0.005;
Point(1) = {0, 0, 0, h};
Point(2) = {R, 0, 0, h}; Point(3) = {L, 0, 0, h};
Point(4) = {L, L, 0, h}; Point(5) = {0, L, 0, h};
Point(6) = {0, R, 0, h};
Line(1) = {2, 3}; Line(2) = {3, 4}; Line(3) = {4, 5}; Line(4) = {5, 6};
Circle(5) = {6, 1, 2};
Curve Loop(1) = {1, 2, 3, 4, 5};
Plane Surface(1) = {1};
Recombine Surface{1};
Physical Curve("bottom") = {1};
Physical Curve("right") = {2};
Physical Curve("top") = {3};
Physical Curve("left") = {4};
Physical Curve("hole") = {5};
Physical Surface("plate") = {1};
