// A 10 x 8 x 6 mm box with a cylindrical bore of radius 2 mm along z, in tetrahedra of
// about 2.5 mm: a curved surface in 3-D. gmsh -3 -format msh41 box_tet.geo
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 0.010, 0.008, 0.006};
Cylinder(2) = {0.005, 0.004, 0, 0, 0, 0.006, 0.002};
BooleanDifference(3) = {Volume{1}; Delete;}{Volume{2}; Delete;};
Mesh.MeshSizeMin = 0.0025;
Mesh.MeshSizeMax = 0.0025;
Physical Surface("all") = Surface{:};
Physical Volume("body") = {3};
