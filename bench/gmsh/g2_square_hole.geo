// G2 of geometries.md: [-1,1]^2 minus the disk r = 0.5, uniform size hs (gmsh -setnumber hs H).
Mesh.Algorithm = 6;  // Frontal-Delaunay
Point(1) = {-1, -1, 0, hs}; Point(2) = {1, -1, 0, hs}; Point(3) = {1, 1, 0, hs}; Point(4) = {-1, 1, 0, hs};
Point(5) = {0, 0, 0, hs};
Point(6) = {0.5, 0, 0, hs}; Point(7) = {0, 0.5, 0, hs}; Point(8) = {-0.5, 0, 0, hs}; Point(9) = {0, -0.5, 0, hs};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Circle(5) = {6, 5, 7}; Circle(6) = {7, 5, 8}; Circle(7) = {8, 5, 9}; Circle(8) = {9, 5, 6};
Curve Loop(1) = {1, 2, 3, 4};
Curve Loop(2) = {5, 6, 7, 8};
Plane Surface(1) = {1, 2};
Physical Surface("domain", 1) = {1};
Physical Curve("outer", 2) = {1, 2, 3, 4};
Physical Curve("hole", 3) = {5, 6, 7, 8};
