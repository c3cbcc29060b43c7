// Hemisphere of radius R (3D), pole at the origin touching the flat z = 0, base at z = R.
// Size h_contact within r_fine of the pole and, when `layer` is given, within `layer` of the
// spherical surface (a refined surface layer over the contact region, so a fine contact mesh
// does not refine the ball under it); growing by `growth` per unit distance beyond, up to
// h_far. Physical groups: body (volume), surface (the spherical surface), base (z = R).
SetFactory("OpenCASCADE");
DefineConstant[ R = {1000.0, Min 10, Name "R"}, h_contact = {12.0, Min 0.5, Name "h_contact"}, r_fine = {60.0, Min 0, Name "r_fine"}, growth = {0.3, Min 0, Name "growth"}, h_far = {150.0, Min 1, Name "h_far"}, layer = {1e9, Min 0, Name "layer"} ];
Sphere(1) = {0, 0, R, R, -Pi/2, 0, 2*Pi};
e = 1e-6 * R;
Physical Volume("body") = {1};
Physical Surface("base") = Surface In BoundingBox{-R - e, -R - e, R - e, R + e, R + e, R + e};
all() = Surface{:};
base() = Surface In BoundingBox{-R - e, -R - e, R - e, R + e, R + e, R + e};
Physical Surface("surface") = {all()};
Physical Surface("surface") -= {base()};
Field[1] = MathEval;
// excess distance: beyond r_fine from the pole, or deeper than `layer` below the surface
Field[1].F = Sprintf("min(%g, %g + %g * max(0, max(sqrt(x*x + y*y + z*z) - %g, %g - sqrt(x*x + y*y + (z - %g)*(z - %g)) - %g)))", h_far, h_contact, growth, r_fine, R, R, R, layer);
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
