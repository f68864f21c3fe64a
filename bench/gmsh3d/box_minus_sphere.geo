// The cube [-1,1]^3 minus the ball of radius 0.5, uniform size hs (gmsh -setnumber hs H):
// meshbench3d's "box_minus_sphere".
SetFactory("OpenCASCADE");
Box(1) = {-1, -1, -1, 2, 2, 2};
Sphere(2) = {0, 0, 0, 0.5};
BooleanDifference(3) = { Volume{1}; Delete; }{ Volume{2}; Delete; };
Mesh.MeshSizeMin = hs;
Mesh.MeshSizeMax = hs;
Physical Volume("domain", 1) = {3};
