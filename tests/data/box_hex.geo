// A 10 x 8 x 6 mm box in 5 x 4 x 3 hexahedra, one corner moved so the faces are not all
// planar. gmsh -3 -format msh41 box_hex.geo
Point(1) = {0, 0, 0}; Point(2) = {0.010, 0, 0}; Point(3) = {0.010, 0.008, 0}; Point(4) = {0, 0.008, 0.001};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Surface(1) = {1};
Transfinite Curve{1, 3} = 6; Transfinite Curve{2, 4} = 5;
Transfinite Surface{1}; Recombine Surface{1};
out[] = Extrude{0, 0, 0.006}{Surface{1}; Layers{3}; Recombine;};
Physical Surface("bottom") = {1};
Physical Surface("top") = {out[0]};
Physical Surface("sides") = {out[2], out[3], out[4], out[5]};
Physical Volume("body") = {out[1]};
