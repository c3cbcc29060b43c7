// A half-space (a cylinder of radius and depth L) under a disc of radius a at its surface, in
// the r-z half plane (x = r, y = z), surface at z = 0. Refined to h_disc within r_fine of the
// disc's edge, growing by `growth` per unit distance beyond, up to h_far.
// Groups: body, disc (0 <= r <= a on z = 0), free (a <= r <= L on z = 0), base (z = -L),
// side (r = L).
DefineConstant[ a = {1.0, Name "a"}, L = {40.0, Name "L"}, h_disc = {0.05, Name "h_disc"},
                r_fine = {1.5, Name "r_fine"}, growth = {0.3, Name "growth"}, h_far = {4.0, Name "h_far"} ];
Point(1) = {0, 0, 0, h_disc};
Point(2) = {a, 0, 0, h_disc};
Point(3) = {L, 0, 0, h_far};
Point(4) = {L, -L, 0, h_far};
Point(5) = {0, -L, 0, h_far};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 5};
Line(5) = {5, 1};
Curve Loop(1) = {-5, -4, -3, -2, -1};
Plane Surface(1) = {1};
Field[1] = Distance;
Field[1].PointsList = {1, 2};
Field[1].CurvesList = {1};
Field[1].NumPointsPerCurve = 200;
Field[2] = MathEval;
Field[2].F = Sprintf("Min(%g, %g + %g * Max(F1 - %g, 0))", h_far, h_disc, growth, r_fine);
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Physical Surface("body") = {1};
Physical Curve("disc") = {1};
Physical Curve("free") = {2};
Physical Curve("base") = {4};
Physical Curve("side") = {3};
