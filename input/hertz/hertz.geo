// The validation case of the paper (section 6): a steel cylinder of radius
// R above a steel plate with a minimum initial gap g0, in mm. The cylinder
// is modelled as the lower half disk; its flat top edge (the diameter) is
// the loaded edge. Meshes are graded toward the contact point and do not
// match across the contact (the cylinder is meshed finer than the plate).
//
// Parameters (gmsh -setnumber NAME VALUE):
//   h       element size at the contact (mm)          default 0.1
//   ratio   cylinder size / plate size at the contact  default 0.6
//   Lp      plate half width (mm)                      default 40
//   Hp      plate depth (mm)                           default 40
//   quads   1 = quadrilaterals, 0 = triangles          default 1
DefineConstant[ h = 0.1, ratio = 0.6, Lp = 40, Hp = 40, quads = 1 ];
R = 10;
g0 = 0.1;
far = R / 4;      // element size far from the contact
zone = 2.5;       // half width of the finely meshed zone (a < 1.6 at the peak)

// plate: top edge y = 0
Point(1) = {-Lp, -Hp, 0, far};
Point(2) = {0, -Hp, 0, far};
Point(3) = {Lp, -Hp, 0, far};
Point(4) = {Lp, 0, 0, far};
Point(5) = {0, 0, 0, h};
Point(6) = {-Lp, 0, 0, far};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 5};
Line(5) = {5, 6};
Line(6) = {6, 1};
Curve Loop(1) = {1, 2, 3, 4, 5, 6};
Plane Surface(1) = {1};

// cylinder: lower half disk, centre (0, R + g0)
Point(10) = {0, R + g0, 0, far};
Point(11) = {-R, R + g0, 0, far};
Point(12) = {0, g0, 0, ratio * h};
Point(13) = {R, R + g0, 0, far};
Circle(10) = {11, 10, 12};
Circle(11) = {12, 10, 13};
Line(12) = {13, 10};
Line(13) = {10, 11};
Curve Loop(2) = {10, 11, 12, 13};
Plane Surface(2) = {2};

// grading: fine within `zone` of the contact point, coarser away from it
Field[1] = Distance;
Field[1].PointsList = {5};
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = h;
Field[2].SizeMax = far;
Field[2].DistMin = zone;
Field[2].DistMax = 2 * R;
Field[3] = Distance;
Field[3].PointsList = {12};
Field[4] = Threshold;
Field[4].InField = 3;
Field[4].SizeMin = ratio * h;
Field[4].SizeMax = far;
Field[4].DistMin = zone;
Field[4].DistMax = R;
Field[5] = Restrict;
Field[5].InField = 2;
Field[5].SurfacesList = {1};
Field[5].CurvesList = {1, 2, 3, 4, 5, 6};
Field[6] = Restrict;
Field[6].InField = 4;
Field[6].SurfacesList = {2};
Field[6].CurvesList = {10, 11, 12, 13};
Field[7] = Min;
Field[7].FieldsList = {5, 6};
Background Field = 7;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;

If (quads)
  Recombine Surface{1, 2};
  Mesh.Algorithm = 6;
EndIf

Physical Curve("PLATE_TOP") = {4, 5};
Physical Curve("PLATE_BOTTOM") = {1, 2};
Physical Point("PLATE_ANCHOR") = {2};
Physical Curve("CYL_ARC") = {10, 11};
Physical Curve("CYL_TOP") = {12, 13};
Physical Surface("PLATE") = {1};
Physical Surface("CYLINDER") = {2};
