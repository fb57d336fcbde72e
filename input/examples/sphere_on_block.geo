// A steel sphere pushed by a pressure onto a steel block, axisymmetric:
// the r-z half plane (r = x >= 0, z = y), mm. The sphere (radius R) is its
// lower half, a quarter disk in the r-z plane whose flat top (the
// equatorial plane, z = R) carries the pressure; it touches the block
// (a cylinder of radius Lb and depth Hb, top face z = 0) at its pole, the
// origin. Both bodies are graded toward the contact point; the meshes do
// not match across the contact.
//
//   gmsh -2 -format inp -setnumber Mesh.SaveGroupsOfNodes 1 \
//        -o sphere_on_block_mesh.inp sphere_on_block.geo
//
// gmsh names the quadrilaterals CPS4; STATE=AXISYMMETRIC on the deck's
// sections makes them CAX4.
//
// Parameters (gmsh -setnumber NAME VALUE):
//   h       element size at the contact point, both bodies (mm)  default 0.04
//   ratio   sphere size / block size at the contact              default 1
//   zone    radius of the finely meshed zone (mm)                default 1.2
//   Lb, Hb  radius and depth of the block (mm)                   default 30, 30
DefineConstant[ h = 0.04, ratio = 1, zone = 1.2, Lb = 30, Hb = 30 ];
R = 10;
far = R / 4;

// block: top face z = 0
Point(1) = {0, -Hb, 0, far};
Point(2) = {Lb, -Hb, 0, far};
Point(3) = {Lb, 0, 0, far};
Point(4) = {0, 0, 0, h};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};

// sphere: lower quarter of the r-z disk, centre (0, R), pole at the origin
Point(10) = {0, R, 0, far};
Point(11) = {0, 0, 0, ratio * h};
Point(12) = {R, R, 0, far};
Circle(10) = {11, 10, 12};
Line(11) = {12, 10};
Line(12) = {10, 11};
Curve Loop(2) = {10, 11, 12};
Plane Surface(2) = {2};

// size h out to `zone` from the contact point, growing to `far`
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

Physical Curve("BLOCK_TOP") = {3};
Physical Curve("BLOCK_BOTTOM") = {1};
Physical Curve("BLOCK_AXIS") = {4};
Physical Curve("SPHERE_ARC") = {10};
Physical Curve("EQUATOR") = {11};
Physical Curve("SPHERE_AXIS") = {12};
Physical Surface("BLOCK") = {1};
Physical Surface("SPHERE") = {2};
