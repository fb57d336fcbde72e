// NAFEMS contact benchmark 1 (cylinder roller, frictionless case): a steel
// cylinder of radius R pressed onto an aluminium block, plane strain. Half
// model: everything right of the symmetry plane x = 0. Units: mm.
//
// The block's top edge is y = 0; the cylinder touches it at the origin
// (or stands g0 above it). Both bodies are meshed with quadrilaterals graded
// toward the contact point, the cylinder at `ratio` times the block's size
// so that its arc (the slave surface) is the finer side.
//
// Parameters (gmsh -setnumber NAME VALUE):
//   h      element size of the block at the contact (mm)   default 0.3
//   ratio  cylinder size / block size at the contact       default 0.5
//   g0     initial gap between cylinder and block (mm)     default 0
//   W, H   block half width and depth (mm)                 default 100, 100
DefineConstant[ h = 0.3, ratio = 0.5, g0 = 0, W = 100, H = 100 ];
R = 50;
far = 12;        // element size far from the contact
zone = 9;        // the fine zone: 1.5 times the half-width a = 6.21

// block
Point(1) = {0, -H, 0, far};
Point(2) = {W, -H, 0, far};
Point(3) = {W, 0, 0, far};
Point(4) = {0, 0, 0, h};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};

// right half of the cylinder, centre (0, R + g0)
Point(10) = {0, R + g0, 0, far};
Point(11) = {0, g0, 0, ratio * h};
Point(12) = {R, R + g0, 0, far};
Point(13) = {0, 2 * R + g0, 0, far};
Circle(10) = {11, 10, 12};
Circle(11) = {12, 10, 13};
Line(12) = {13, 10};
Line(13) = {10, 11};
Curve Loop(2) = {10, 11, 12, 13};
Plane Surface(2) = {2};

// size: s(d) grows linearly from the contact size to `far`, starting at
// the edge of the fine zone, d the distance to the contact point
Field[1] = Distance;
Field[1].PointsList = {4};
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = h;
Field[2].SizeMax = far;
Field[2].DistMin = zone;
Field[2].DistMax = 6 * zone;
Field[3] = Restrict;
Field[3].InField = 2;
Field[3].SurfacesList = {1};
Field[3].CurvesList = {1, 2, 3, 4};

Field[11] = Distance;
Field[11].PointsList = {11};
Field[12] = Threshold;
Field[12].InField = 11;
Field[12].SizeMin = ratio * h;
Field[12].SizeMax = far;
Field[12].DistMin = zone;
Field[12].DistMax = 6 * zone;
Field[13] = Restrict;
Field[13].InField = 12;
Field[13].SurfacesList = {2};
Field[13].CurvesList = {10, 11, 12, 13};

Field[20] = Min;
Field[20].FieldsList = {3, 13};
Background Field = 20;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Recombine Surface{1, 2};
Mesh.Algorithm = 6;

Physical Surface("BLOCK") = {1};
Physical Curve("BLOCK_TOP") = {3};
Physical Curve("BLOCK_BOTTOM") = {1};
Physical Curve("BLOCK_SYM") = {4};
Physical Surface("CYLINDER") = {2};
Physical Curve("CYL_ARC") = {10};
Physical Curve("CYL_SYM") = {12, 13};
Physical Point("CYL_TOP") = {13};
