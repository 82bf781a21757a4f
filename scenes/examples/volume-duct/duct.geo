// A rectangular duct, 2 x 0.6 x 0.6, meshed in tetrahedra by Gmsh: the volume mesh of the
// volume-duct sample scene. Remake duct.msh with: gmsh -3 -format msh41 duct.geo -o duct.msh
SetFactory("OpenCASCADE");
Box(1) = {0, -0.3, 0, 2, 0.6, 0.6};
Mesh.MeshSizeMin = 0.15;
Mesh.MeshSizeMax = 0.15;
Mesh.Binary = 0;
Physical Surface("inlet") = {1};
Physical Surface("outlet") = {2};
Physical Surface("walls") = {3, 4, 5, 6};
Physical Volume("fluid") = {1};
