// Prismatic cantilever L x B x H along x. Groups: body, clamp (x = 0), tip (x = L).
SetFactory("OpenCASCADE");
DefineConstant[ L = {10.0, Min 1e-6, Name "L"}, B = {1.0, Min 1e-6, Name "B"}, H = {1.0, Min 1e-6, Name "H"}, h = {0.5, Min 0.01, Name "h"} ];
Box(1) = {0, 0, 0, L, B, H};
e = 1e-6 * L;
Physical Volume("body") = {1};
Physical Surface("clamp") = Surface In BoundingBox{-e, -e, -e, e, B + e, H + e};
Physical Surface("tip") = Surface In BoundingBox{L - e, -e, -e, L + e, B + e, H + e};
MeshSize{:} = h;
