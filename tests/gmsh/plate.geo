// Plate in uniaxial tension for the gmsh-import test: a triangle half and
// a recombined (quadrilateral) half, with physical groups for the edges.
lc = 0.25;
Point(1) = {0, 0, 0, lc};
Point(2) = {1, 0, 0, lc};
Point(3) = {2, 0, 0, lc};
Point(4) = {2, 1, 0, lc};
Point(5) = {1, 1, 0, lc};
Point(6) = {0, 1, 0, lc};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4};
Line(4) = {4, 5}; Line(5) = {5, 6}; Line(6) = {6, 1}; Line(7) = {2, 5};
Curve Loop(1) = {1, 7, 5, 6};
Plane Surface(1) = {1};
Curve Loop(2) = {2, 3, 4, -7};
Plane Surface(2) = {2};
Recombine Surface{2};
Physical Curve("LEFT") = {6};
Physical Curve("RIGHT") = {3};
Physical Curve("BOTTOM") = {1, 2};
Physical Surface("PLATE") = {1, 2};
