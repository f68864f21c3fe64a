// The unit ball, uniform size hs (gmsh -setnumber hs H): meshbench3d's "ball".
SetFactory("OpenCASCADE");
Sphere(1) = {0, 0, 0, 1};
Mesh.MeshSizeMin = hs;
Mesh.MeshSizeMax = hs;
Physical Volume("domain", 1) = {1};
Physical Surface("sphere1", 2) = {1};
