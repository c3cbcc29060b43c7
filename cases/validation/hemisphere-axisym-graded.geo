// Hemisphere of radius R in the r-z half plane (x = r, y = z), pole at the origin touching
// the flat z = 0, base at z = R, graded by the size field of the 3D quarter
// (hemisphere-quarter-3d.geo), so that an axisymmetric twin of a 3D run has the same element
// sizes: h_contact within r_fine of the pole and, when `layer` is given, within `layer` of
// the spherical surface; growing by `growth` per unit distance beyond, up to h_far.
// Physical groups: body, surface (the spherical boundary), base (z = R), axis (r = 0).
DefineConstant[ R = {1000.0, Min 10, Name "R"}, h_contact = {4.0, Min 0.05, Name "h_contact"}, r_fine = {80.0, Min 0, Name "r_fine"}, h_far = {150.0, Min 1, Name "h_far"}, growth = {0.4, Min 0, Name "growth"}, layer = {1e9, Min 0, Name "layer"} ];
Point(1) = {0, 0, 0, h_contact};
Point(2) = {0, R, 0, h_far};
Point(3) = {R, R, 0, h_far};
Circle(1) = {1, 2, 3};
Line(2) = {3, 2};
Line(3) = {2, 1};
Curve Loop(1) = {1, 2, 3};
Plane Surface(1) = {1};
Field[1] = MathEval;
Field[1].F = Sprintf("min(%g, %g + %g * max(0, max(sqrt(x*x + y*y) - %g, %g - sqrt(x*x + (y - %g)*(y - %g)) - %g)))", h_far, h_contact, growth, r_fine, R, R, R, layer);
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Physical Surface("body") = {1};
Physical Curve("surface") = {1};
Physical Curve("base") = {2};
Physical Curve("axis") = {3};
