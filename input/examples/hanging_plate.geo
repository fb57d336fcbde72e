// A steel plate hanging on three steel pins with clearance, plane stress,
// mm. The plate (W x H, corner at the origin) has three holes of radius
// Rh along a line near its top edge; in each sits a pin of radius Rp < Rh
// with the same centre (clearance Rh - Rp all around: the plate touches no
// pin). A pin is a disk with a bore of radius Rb whose edge is held.
//
//   gmsh -2 -order 2 -setnumber Mesh.SecondOrderIncomplete 1 -format inp \
//        -setnumber Mesh.SaveGroupsOfNodes 1 -o hanging_plate_mesh.inp hanging_plate.geo
//
// gives 8-node quadrilaterals (CPS8; -order 2 alone gives 9-node ones).
//
// Parameters (gmsh -setnumber NAME VALUE):
//   Rh, Rp  hole and pin radius (mm)                         default 5, 4.95
//   hh, hp  element size on the holes and on the pins (mm)   default 0.5, 0.6
//   hfar    element size away from the holes (mm)           default 8
DefineConstant[ Rh = 5, Rp = 4.95, hh = 0.5, hp = 0.6, hfar = 8 ];
W = 150; H = 80; Rb = 2;
yc = 65;
xc[] = {25, 75, 125};

Point(1) = {0, 0, 0, hfar};
Point(2) = {W, 0, 0, hfar};
Point(3) = {W, H, 0, hfar};
Point(4) = {0, H, 0, hfar};
// the point load acts at the bottom edge, off the middle
Point(5) = {100, 0, 0, hfar};
Line(1) = {1, 5};
Line(2) = {5, 2};
Line(3) = {2, 3};
Line(4) = {3, 4};
Line(5) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4, 5};

// circle of radius r about (x, y) from four quarter arcs, starting at the
// top; returns its curve loop in `loop` and its arcs in `arcs[]`
Macro CircleLoop
  pc = newp; Point(pc) = {x, y, 0, s};
  p1 = newp; Point(p1) = {x, y + r, 0, s};
  p2 = newp; Point(p2) = {x - r, y, 0, s};
  p3 = newp; Point(p3) = {x, y - r, 0, s};
  p4 = newp; Point(p4) = {x + r, y, 0, s};
  c1 = newc; Circle(c1) = {p1, pc, p2};
  c2 = newc; Circle(c2) = {p2, pc, p3};
  c3 = newc; Circle(c3) = {p3, pc, p4};
  c4 = newc; Circle(c4) = {p4, pc, p1};
  arcs[] = {c1, c2, c3, c4};
  loop = newll; Curve Loop(loop) = arcs[];
Return

holes[] = {};
For k In {0 : 2}
  x = xc[k]; y = yc; r = Rh; s = hh;
  Call CircleLoop;
  holes[] += loop;
  hole_arcs~{k}[] = arcs[];
EndFor
Plane Surface(1) = {1, holes[]};

For k In {0 : 2}
  x = xc[k]; y = yc; r = Rp; s = hp;
  Call CircleLoop;
  pin_loop = loop;
  pin_arcs~{k}[] = arcs[];
  r = Rb; s = 2 * hp;
  Call CircleLoop;
  bore_arcs~{k}[] = arcs[];
  Plane Surface(10 + k) = {pin_loop, loop};
EndFor

// size hh on the holes growing to hfar 15 mm away; hp on the pins
Field[1] = Distance;
Field[1].CurvesList = {hole_arcs~{0}[], hole_arcs~{1}[], hole_arcs~{2}[]};
Field[1].NumPointsPerCurve = 200;
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = hh;
Field[2].SizeMax = hfar;
Field[2].DistMin = 1;
Field[2].DistMax = 15;
Field[3] = Restrict;
Field[3].InField = 2;
Field[3].SurfacesList = {1};
Field[3].CurvesList = {1, 2, 3, 4, 5, hole_arcs~{0}[], hole_arcs~{1}[], hole_arcs~{2}[]};
Field[4] = MathEval;
Field[4].F = Sprintf("%g", hp);
Field[5] = Restrict;
Field[5].InField = 4;
Field[5].SurfacesList = {10, 11, 12};
Field[5].CurvesList = {pin_arcs~{0}[], pin_arcs~{1}[], pin_arcs~{2}[],
                       bore_arcs~{0}[], bore_arcs~{1}[], bore_arcs~{2}[]};
Field[7] = Min;
Field[7].FieldsList = {3, 5};
Background Field = 7;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Mesh.Algorithm = 6;
Mesh.RecombineAll = 1;
Mesh.RecombinationAlgorithm = 1;

Physical Surface("PLATE") = {1};
Physical Surface("PINS") = {10, 11, 12};
For k In {0 : 2}
  Physical Curve(Sprintf("HOLE%g", k + 1)) = {hole_arcs~{k}[]};
  Physical Curve(Sprintf("PIN%g", k + 1)) = {pin_arcs~{k}[]};
  Physical Curve(Sprintf("BORE%g", k + 1)) = {bore_arcs~{k}[]};
EndFor
Physical Point("LOAD_POINT") = {5};
