// A block W x W x L (L along z) whose bottom face meets a rigid flat. Groups: body, bottom
// (z = 0), top (z = L), x0, x1, y0, y1 (lateral faces).
SetFactory("OpenCASCADE");
DefineConstant[ L = {1.0, Min 1e-3, Name "L"}, W = {1.0, Min 1e-3, Name "W"}, h = {0.5, Min 0.01, Name "h"} ];
Box(1) = {0, 0, 0, W, W, L};
e = 1e-6 * W;
Physical Volume("body") = {1};
Physical Surface("bottom") = Surface In BoundingBox{-e, -e, -e, W + e, W + e, e};
Physical Surface("top") = Surface In BoundingBox{-e, -e, L - e, W + e, W + e, L + e};
Physical Surface("x0") = Surface In BoundingBox{-e, -e, -e, e, W + e, L + e};
Physical Surface("x1") = Surface In BoundingBox{W - e, -e, -e, W + e, W + e, L + e};
Physical Surface("y0") = Surface In BoundingBox{-e, -e, -e, W + e, e, L + e};
Physical Surface("y1") = Surface In BoundingBox{-e, W - e, -e, W + e, W + e, L + e};
MeshSize{:} = h;
