// The validation case of the paper (section 6): a steel cylinder of radius
// R above a steel plate with a minimum initial gap g0, in mm. The cylinder
// is modelled as the lower half disk; its flat top edge (the diameter) is
// the loaded edge. Meshes are graded toward the contact point and do not
// match across the contact (the cylinder is meshed finer than the plate).
//
// Parameters (gmsh -setnumber NAME VALUE):
//   h       element size at the contact (mm)          default 0.05
//   ratio   cylinder size / plate size at the contact  default 0.5
//   Lp      plate half width (mm)                      default 40
//   Hp      plate depth (mm)                           default 40
//   quads   1 = quadrilaterals, 0 = triangles          default 1
DefineConstant[ h = 0.05, ratio = 0.5, Lp = 40, Hp = 40, quads = 1 ];
R = 10;
g0 = 0.1;
far = R / 4;      // element size far from the contact
zone = 2.5;       // half width of the finely meshed zone (a = 1.3 at the peak)

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

// grading: the size grows from h/2 at the contact point to h at 1.3 mm
// (the half-width at the peak load), stays h out to `zone`, then grows to
// `far`. Fields 1-5: plate; 11-15: cylinder (sizes times `ratio`).
Field[1] = Distance;
Field[1].PointsList = {5};
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = 0.5 * 1 * h;
Field[2].SizeMax = 1 * h;
Field[2].DistMin = 0;
Field[2].DistMax = 1.3;
Field[3] = Threshold;
Field[3].InField = 1;
Field[3].SizeMin = 1 * h;
Field[3].SizeMax = far;
Field[3].DistMin = zone;
Field[3].DistMax = 2 * R;
Field[4] = MathEval;
Field[4].F = Sprintf("F2 + F3 - %g", 1 * h);
Field[5] = Restrict;
Field[5].InField = 4;
Field[5].SurfacesList = {1};
Field[5].CurvesList = {1, 2, 3, 4, 5, 6};

Field[11] = Distance;
Field[11].PointsList = {12};
Field[12] = Threshold;
Field[12].InField = 11;
Field[12].SizeMin = 0.5 * ratio * h;
Field[12].SizeMax = ratio * h;
Field[12].DistMin = 0;
Field[12].DistMax = 1.3;
Field[13] = Threshold;
Field[13].InField = 11;
Field[13].SizeMin = ratio * h;
Field[13].SizeMax = far;
Field[13].DistMin = zone;
Field[13].DistMax = R;
Field[14] = MathEval;
Field[14].F = Sprintf("F12 + F13 - %g", ratio * h);
Field[15] = Restrict;
Field[15].InField = 14;
Field[15].SurfacesList = {2};
Field[15].CurvesList = {10, 11, 12, 13};

Field[7] = Min;
Field[7].FieldsList = {5, 15};
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
