// A block 1 x 1 x L (L along z) whose bottom face meets a rigid flat. Groups: body, bottom
// (z = 0), top (z = L), x0, x1, y0, y1 (lateral faces).
SetFactory("OpenCASCADE");
DefineConstant[ L = {1.0, Min 1e-3, Name "L"}, h = {0.5, Min 0.01, Name "h"} ];
Box(1) = {0, 0, 0, 1, 1, L};
e = 1e-6;
Physical Volume("body") = {1};
Physical Surface("bottom") = Surface In BoundingBox{-e, -e, -e, 1 + e, 1 + e, e};
Physical Surface("top") = Surface In BoundingBox{-e, -e, L - e, 1 + e, 1 + e, L + e};
Physical Surface("x0") = Surface In BoundingBox{-e, -e, -e, e, 1 + e, L + e};
Physical Surface("x1") = Surface In BoundingBox{1 - e, -e, -e, 1 + e, 1 + e, L + e};
Physical Surface("y0") = Surface In BoundingBox{-e, -e, -e, 1 + e, e, L + e};
Physical Surface("y1") = Surface In BoundingBox{-e, 1 - e, -e, 1 + e, 1 + e, L + e};
MeshSize{:} = h;
