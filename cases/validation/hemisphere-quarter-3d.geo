// Quarter of a hemisphere of radius R (3D): x >= 0, y >= 0, pole at the origin touching the flat
// z = 0, base at z = R. Size h_contact within r_fine of the pole and, when `layer` is given,
// within `layer` of the spherical surface (a refined surface layer over the contact region);
// growing by `growth` per unit distance beyond, up to h_far. Groups: body, surface (spherical), base (z = R), sym_x (x = 0),
// sym_y (y = 0).
SetFactory("OpenCASCADE");
DefineConstant[ R = {1000.0, Min 10, Name "R"}, h_contact = {8.0, Min 0.5, Name "h_contact"}, r_fine = {40.0, Min 0, Name "r_fine"}, growth = {0.4, Min 0, Name "growth"}, h_far = {150.0, Min 1, Name "h_far"}, layer = {1e9, Min 0, Name "layer"} ];
Sphere(1) = {0, 0, R, R, -Pi/2, 0, Pi/2};
e = 1e-6 * R;
Physical Volume("body") = {1};
Physical Surface("base") = Surface In BoundingBox{-e, -e, R - e, R + e, R + e, R + e};
Physical Surface("sym_x") = Surface In BoundingBox{-e, -e, -e, e, R + e, R + e};
Physical Surface("sym_y") = Surface In BoundingBox{-e, -e, -e, R + e, e, R + e};
all() = Surface{:};
flat() = Surface In BoundingBox{-e, -e, R - e, R + e, R + e, R + e};
flat() += Surface In BoundingBox{-e, -e, -e, e, R + e, R + e};
flat() += Surface In BoundingBox{-e, -e, -e, R + e, e, R + e};
Physical Surface("surface") = {all()};
Physical Surface("surface") -= {flat()};
Field[1] = MathEval;
// excess distance: beyond r_fine from the pole, or deeper than `layer` below the surface
Field[1].F = Sprintf("min(%g, %g + %g * max(0, max(sqrt(x*x + y*y + z*z) - %g, %g - sqrt(x*x + y*y + (z - %g)*(z - %g)) - %g)))", h_far, h_contact, growth, r_fine, R, R, R, layer);
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
