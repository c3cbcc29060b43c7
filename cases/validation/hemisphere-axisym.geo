// Hemisphere of radius R in the r-z half plane (x = r, y = z), pole at the origin touching
// the flat z = 0, base at z = R. Graded: size h_contact within r_fine of the pole, growing to
// h_far. Physical groups: body, surface (the spherical boundary), base (z = R), axis (r = 0).
DefineConstant[ R = {1000.0, Min 10, Name "R"}, h_contact = {4.0, Min 0.05, Name "h_contact"}, r_fine = {80.0, Min 0, Name "r_fine"}, h_far = {100.0, Min 1, Name "h_far"} ];
Point(1) = {0, 0, 0, h_contact};
Point(2) = {0, R, 0, h_far};
Point(3) = {R, R, 0, h_far};
Circle(1) = {1, 2, 3};
Line(2) = {3, 2};
Line(3) = {2, 1};
Curve Loop(1) = {1, 2, 3};
Plane Surface(1) = {1};
Field[1] = Distance;
Field[1].PointsList = {1};
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = h_contact;
Field[2].SizeMax = h_far;
Field[2].DistMin = r_fine;
Field[2].DistMax = 6 * r_fine;
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Physical Surface("body") = {1};
Physical Curve("surface") = {1};
Physical Curve("base") = {2};
Physical Curve("axis") = {3};
