// The whole plate of examples/plate_with_hole.yaml as a body-fitted mesh: a 100 mm square
// minus a disc of R = 5 mm at its centre, unstructured first-order quadrangles of size h.
//   gmsh -2 -format msh41 plate_mesh.geo -setnumber h 0.002 -o plate_mesh_h2.msh
//   gmsh -2 -format msh41 plate_mesh.geo -setnumber h 0.001 -o plate_mesh_h1.msh
If (!Exists(h))
  h = 0.002;
EndIf
L = 0.1; R = 0.005; c = 0.05;
Point(1) = {0, 0, 0, h}; Point(2) = {L, 0, 0, h}; Point(3) = {L, L, 0, h}; Point(4) = {0, L, 0, h};
Point(5) = {c, c, 0, h};
Point(6) = {c + R, c, 0, h}; Point(7) = {c, c + R, 0, h}; Point(8) = {c - R, c, 0, h}; Point(9) = {c, c - R, 0, h};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Circle(5) = {6, 5, 7}; Circle(6) = {7, 5, 8}; Circle(7) = {8, 5, 9}; Circle(8) = {9, 5, 6};
Curve Loop(1) = {1, 2, 3, 4};
Curve Loop(2) = {5, 6, 7, 8};
Plane Surface(1) = {1, 2};
Recombine Surface{1};
Physical Curve("bottom") = {1};
Physical Curve("right") = {2};
Physical Curve("top") = {3};
Physical Curve("left") = {4};
Physical Curve("hole") = {5, 6, 7, 8};
Physical Surface("plate") = {1};
