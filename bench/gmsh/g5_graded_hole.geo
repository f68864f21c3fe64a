// G5 of geometries.md: G2's domain with edge length hs * min(4 sqrt(x^2 + y^2) - 1, 2), as
// examples/g5_graded_hole.textproto (gmsh -setnumber hs H).
SetFactory("OpenCASCADE");
Mesh.Algorithm = 6;  // Frontal-Delaunay
Rectangle(1) = {-1, -1, 0, 2, 2};
Disk(2) = {0, 0, 0, 0.5, 0.5};
BooleanDifference(3) = { Surface{1}; Delete; }{ Surface{2}; Delete; };
Field[1] = MathEval;
Field[1].F = Sprintf("%.17g * Min(4 * Sqrt(x * x + y * y) - 1, 2)", hs);
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
