// Cattaneo-Mindlin partial slip (tests/test_friction.py): a cylinder of
// radius R (the lower half disk, its flat top the diameter) touching a
// plate at the origin, as input/hertz/hertz.geo meshes the flagship but
// with R a parameter, no initial gap and the fine zone sized for a
// contact half-width a of about 0.5 mm. A large R (100 mm: a/R = 0.005)
// keeps the finite bodies close to Hertz's half-spaces: the normal and
// tangential problems of two bodies of one material decouple only for
// half-spaces (with R = 10 mm and a = 0.94 mm the pressing alone left a
// shear of 6.7 % of mu p0, rms over the contact).
//
// Parameters (gmsh -setnumber NAME VALUE):
//   h      plate element size at the contact (mm)          default 0.025
//   ratio  cylinder size / plate size at the contact        default 0.5
//   R      cylinder radius (mm)                             default 100
//   Lp     plate half width (mm)                            default 4 R
//   Hp     plate depth (mm)                                 default 2 R
//   amax   the size grows from h/2 at the contact to h here default 0.6
//   zone   half width of the zone meshed at h at most       default 1
DefineConstant[ h = 0.025, ratio = 0.5, R = 100, amax = 0.6, zone = 1 ];
DefineConstant[ Lp = 4 * R, Hp = 2 * R ];
far = R / 4;

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

// cylinder: lower half disk, centre (0, R), touching the plate at (0, 0)
Point(10) = {0, R, 0, far};
Point(11) = {-R, R, 0, far};
Point(12) = {0, 0, 0, ratio * h};
Point(13) = {R, R, 0, far};
Circle(10) = {11, 10, 12};
Circle(11) = {12, 10, 13};
Line(12) = {13, 10};
Line(13) = {10, 11};
Curve Loop(2) = {10, 11, 12, 13};
Plane Surface(2) = {2};

// sizes as in hertz.geo: h/2 at the contact growing to h at amax, h out to
// zone, then growing to far. Fields 1-5: plate; 11-15: cylinder.
Field[1] = Distance;
Field[1].PointsList = {5};
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = 0.5 * h;
Field[2].SizeMax = h;
Field[2].DistMin = 0;
Field[2].DistMax = amax;
Field[3] = Threshold;
Field[3].InField = 1;
Field[3].SizeMin = h;
Field[3].SizeMax = far;
Field[3].DistMin = zone;
Field[3].DistMax = 2 * R;
Field[4] = MathEval;
Field[4].F = Sprintf("F2 + F3 - %g", h);
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
Field[12].DistMax = amax;
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
Recombine Surface{1, 2};
Mesh.Algorithm = 6;

Physical Curve("PLATE_TOP") = {4, 5};
Physical Curve("PLATE_BOTTOM") = {1, 2};
Physical Curve("CYL_ARC") = {10, 11};
Physical Curve("CYL_TOP") = {12, 13};
Physical Surface("PLATE") = {1};
Physical Surface("CYLINDER") = {2};
