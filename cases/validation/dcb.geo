// One arm of a mode-I double cantilever beam (the symmetric half): length L, width B,
// thickness H, initial crack a0 from the loaded end x = 0. The ligament (z = 0, x > a0) is
// bonded to the symmetry plane. Fine mesh h_fine in the band a0 - 5 < x < x_fine, z < 2 H / 5.
// Groups: body, ligament, far_end (x = L), load_line (x = 0, z = 0), load_end (the face x = 0).
SetFactory("OpenCASCADE");
DefineConstant[ L = {100.0, Min 1, Name "L"}, B = {2.0, Min 0.01, Name "B"}, H = {5.0, Min 0.01, Name "H"}, a0 = {30.0, Min 0, Name "a0"}, h_fine = {1.0, Min 0.05, Name "h_fine"}, h_coarse = {2.5, Min 0.05, Name "h_coarse"}, x_fine = {70.0, Min 0, Name "x_fine"} ];
Box(1) = {0, 0, 0, a0, B, H};
Box(2) = {a0, 0, 0, L - a0, B, H};
BooleanFragments{ Volume{1}; Delete; }{ Volume{2}; Delete; }
e = 1e-6 * L;
Physical Volume("body") = Volume{:};
Physical Surface("ligament") = Surface In BoundingBox{a0 - e, -e, -e, L + e, B + e, e};
Physical Surface("far_end") = Surface In BoundingBox{L - e, -e, -e, L + e, B + e, H + e};
Physical Curve("load_line") = Curve In BoundingBox{-e, -e, -e, e, B + e, e};
Physical Surface("load_end") = Surface In BoundingBox{-e, -e, -e, e, B + e, H + e};
Field[1] = Box;
Field[1].VIn = h_fine;
Field[1].VOut = h_coarse;
Field[1].XMin = a0 - 5;
Field[1].XMax = x_fine;
Field[1].YMin = -1;
Field[1].YMax = B + 1;
Field[1].ZMin = -1;
Field[1].ZMax = 0.4 * H;
Field[1].Thickness = 3;
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
