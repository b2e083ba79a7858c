// A 6 mm cube in unstructured tetrahedra of about 2 mm, a physical group per face: the
// 3-D mesh patch test. gmsh -3 -format msh41 cube_tet.geo
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 0.006, 0.006, 0.006};
Mesh.MeshSizeMin = 0.002;
Mesh.MeshSizeMax = 0.002;
Physical Surface("xmin") = {1};
Physical Surface("xmax") = {2};
Physical Surface("ymin") = {3};
Physical Surface("ymax") = {4};
Physical Surface("zmin") = {5};
Physical Surface("zmax") = {6};
Physical Volume("body") = {1};
