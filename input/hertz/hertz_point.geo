// 3D Hertz point contact through axisymmetry: an elastic sphere of radius
// R pressed on an elastic flat, in the r-z half plane (r = x >= 0, z = y),
// mm. The sphere is its lower half (a quarter disk in the r-z plane) whose
// flat top (the equator) is the loaded edge; the flat is a cylinder of
// radius Lp and depth Hp under the contact point. The bodies touch at the
// axis (no initial gap). Meshes are graded toward the contact point and
// do not match across the contact (the sphere is meshed finer).
//
// Parameters (gmsh -setnumber NAME VALUE):
//   h       element size of the flat at the contact (mm)   default 0.04
//   ratio   sphere size / flat size at the contact          default 0.5
//   zone    radius of the finely meshed zone (mm)           default 1.5
//   Lp, Hp  radius and depth of the flat (mm)               default 40, 40
DefineConstant[ h = 0.04, ratio = 0.5, zone = 1.5, Lp = 40, Hp = 40 ];
R = 10;
far = R / 4;

// flat: top face z = 0
Point(1) = {0, -Hp, 0, far};
Point(2) = {Lp, -Hp, 0, far};
Point(3) = {Lp, 0, 0, far};
Point(4) = {0, 0, 0, h};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};

// sphere: lower quarter of the r-z disk, centre (0, R)
Point(10) = {0, R, 0, far};
Point(11) = {0, 0, 0, ratio * h};
Point(12) = {R, R, 0, far};
Circle(10) = {11, 10, 12};
Line(11) = {12, 10};
Line(12) = {10, 11};
Curve Loop(2) = {10, 11, 12};
Plane Surface(2) = {2};

// grading: size h at the contact point out to `zone`, growing to `far`
Field[1] = Distance;
Field[1].PointsList = {4};
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = h;
Field[2].SizeMax = far;
Field[2].DistMin = zone;
Field[2].DistMax = 2 * R;
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
Field[12].DistMax = R;
Field[13] = Restrict;
Field[13].InField = 12;
Field[13].SurfacesList = {2};
Field[13].CurvesList = {10, 11, 12};
Field[7] = Min;
Field[7].FieldsList = {3, 13};
Background Field = 7;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Recombine Surface{1, 2};
Mesh.Algorithm = 6;

Physical Curve("FLAT_TOP") = {3};
Physical Curve("FLAT_BOTTOM") = {1};
Physical Curve("FLAT_AXIS") = {4};
Physical Curve("SPHERE_ARC") = {10};
Physical Curve("SPHERE_TOP") = {11};
Physical Curve("SPHERE_AXIS") = {12};
Physical Surface("FLAT") = {1};
Physical Surface("SPHERE") = {2};
