// Mode-I double cantilever beam, both arms: [0, L] x [0, B] x [0, 2H], interior surface z = H
// made of the pre-crack (x < a0) and the ligament (x > a0). Fine mesh h_fine in the band
// a0 - 5 < x < x_fine, |z - H| < 0.4 H. Groups: lower, upper (volumes), crack, ligament,
// far_end (x = L), load_top (x = 0, z = 2H), load_bottom (x = 0, z = 0).
SetFactory("OpenCASCADE");
DefineConstant[ L = {100.0, Min 1, Name "L"}, B = {2.0, Min 0.01, Name "B"}, H = {5.0, Min 0.01, Name "H"}, a0 = {30.0, Min 0, Name "a0"}, h_fine = {1.0, Min 0.05, Name "h_fine"}, h_coarse = {2.5, Min 0.05, Name "h_coarse"}, x_fine = {70.0, Min 0, Name "x_fine"} ];
Box(1) = {0, 0, 0, a0, B, H};
Box(2) = {a0, 0, 0, L - a0, B, H};
Box(3) = {0, 0, H, a0, B, H};
Box(4) = {a0, 0, H, L - a0, B, H};
BooleanFragments{ Volume{1, 2, 3, 4}; Delete; }{}
e = 1e-6 * L;
Physical Volume("lower") = Volume In BoundingBox{-e, -e, -e, L + e, B + e, H + e};
Physical Volume("upper") = Volume In BoundingBox{-e, -e, H - e, L + e, B + e, 2 * H + e};
Physical Surface("crack") = Surface In BoundingBox{-e, -e, H - e, a0 + e, B + e, H + e};
Physical Surface("ligament") = Surface In BoundingBox{a0 - e, -e, H - e, L + e, B + e, H + e};
Physical Surface("far_end") = Surface In BoundingBox{L - e, -e, -e, L + e, B + e, 2 * H + e};
Physical Curve("load_top") = Curve In BoundingBox{-e, -e, 2 * H - e, e, B + e, 2 * H + e};
Physical Curve("load_bottom") = Curve In BoundingBox{-e, -e, -e, e, B + e, e};
Field[1] = Box;
Field[1].VIn = h_fine;
Field[1].VOut = h_coarse;
Field[1].XMin = a0 - 5;
Field[1].XMax = x_fine;
Field[1].YMin = -1;
Field[1].YMax = B + 1;
Field[1].ZMin = 0.6 * H;
Field[1].ZMax = 1.4 * H;
Field[1].Thickness = 3;
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
