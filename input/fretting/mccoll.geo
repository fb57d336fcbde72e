// McColl, Ding & Leen (Wear 256, 2004) fretting test as the public
// reproduction models it (illavori/LevelSetWear, examples/05_fretting_mccoll):
// plane strain, mm. A flat 12 x 6 mm (y from -6 to 0) and the lower half
// disk of a cylinder of radius R = 6 mm touching it at the origin, both
// meshed with quadrilaterals of size h over |x| < zone, depth 0.2 mm
// (the reproduction: 0.01 mm over |x| < 0.5 mm), coarser away from it.
DefineConstant[ h = 0.01, zone = 0.5, depth = 0.2, far = 0.75 ];
R = 6;
Point(1) = {-6, -6, 0, far};
Point(2) = {0, -6, 0, far};
Point(3) = {6, -6, 0, far};
Point(4) = {6, 0, 0, far};
Point(5) = {0, 0, 0, h};
Point(6) = {-6, 0, 0, far};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 5};
Line(5) = {5, 6};
Line(6) = {6, 1};
Curve Loop(1) = {1, 2, 3, 4, 5, 6};
Plane Surface(1) = {1};
Point(10) = {0, R, 0, far};
Point(11) = {-R, R, 0, far};
Point(12) = {0, 0, 0, h};
Point(13) = {R, R, 0, far};
Circle(10) = {11, 10, 12};
Circle(11) = {12, 10, 13};
Line(12) = {13, 10};
Line(13) = {10, 11};
Curve Loop(2) = {10, 11, 12, 13};
Plane Surface(2) = {2};
// the fine zone on each side of the contact, restricted to its own body
Field[1] = Box;
Field[1].VIn = h;
Field[1].VOut = far;
Field[1].XMin = -zone; Field[1].XMax = zone;
Field[1].YMin = -depth; Field[1].YMax = 0.0;
Field[1].Thickness = 3;
Field[2] = Restrict;
Field[2].InField = 1;
Field[2].SurfacesList = {1};
Field[2].CurvesList = {1, 2, 3, 4, 5, 6};
Field[11] = Box;
Field[11].VIn = h;
Field[11].VOut = far;
Field[11].XMin = -zone; Field[11].XMax = zone;
Field[11].YMin = 0.0; Field[11].YMax = depth;
Field[11].Thickness = 3;
Field[12] = Restrict;
Field[12].InField = 11;
Field[12].SurfacesList = {2};
Field[12].CurvesList = {10, 11, 12, 13};
Field[7] = Min;
Field[7].FieldsList = {2, 12};
Background Field = 7;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Recombine Surface{1, 2};
Mesh.Algorithm = 6;
Physical Curve("FLAT_TOP") = {4, 5};
Physical Curve("FLAT_BOTTOM") = {1, 2};
Physical Curve("CYL_ARC") = {10, 11};
Physical Curve("CYL_TOP") = {12, 13};
Physical Surface("FLAT") = {1};
Physical Surface("CYLINDER") = {2};
