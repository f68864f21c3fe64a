// examples/plate_with_holes.textproto: [0,4] x [0,2] minus four disks, edge length
// hs * min(3, 1 + 4 d), d the distance to the nearest disk (gmsh -setnumber hs H).
SetFactory("OpenCASCADE");
Mesh.Algorithm = 6;  // Frontal-Delaunay
Rectangle(1) = {0, 0, 0, 4, 2};
Disk(2) = {1.2, 1, 0, 0.45, 0.45};
Disk(3) = {2.7, 1.45, 0, 0.25, 0.25};
Disk(4) = {2.7, 0.55, 0, 0.25, 0.25};
Disk(5) = {3.5, 1, 0, 0.15, 0.15};
BooleanDifference(6) = { Surface{1}; Delete; }{ Surface{2, 3, 4, 5}; Delete; };
Field[1] = MathEval;
Field[1].F = Sprintf(StrCat("%.17g * Min(3, 1 + 4 * Min(Min(Sqrt((x-1.2)^2+(y-1)^2)-0.45, ",
                            "Sqrt((x-2.7)^2+(y-1.45)^2)-0.25), Min(Sqrt((x-2.7)^2+(y-0.55)^2)-0.25, ",
                            "Sqrt((x-3.5)^2+(y-1)^2)-0.15)))"), hs);
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
