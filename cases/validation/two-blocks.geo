// Two unit cubes stacked along z, joined at the interior face z = 1 ("interface").
// Groups: lower, upper, interface, bottom (z = 0), top (z = 2), x0 (x = 0), y0 (y = 0).
SetFactory("OpenCASCADE");
DefineConstant[ h = {0.5, Min 0.01, Name "h"} ];
Box(1) = {0, 0, 0, 1, 1, 1};
Box(2) = {0, 0, 1, 1, 1, 1};
BooleanFragments{ Volume{1, 2}; Delete; }{}
e = 1e-6;
Physical Volume("lower") = Volume In BoundingBox{-e, -e, -e, 1 + e, 1 + e, 1 + e};
Physical Volume("upper") = Volume In BoundingBox{-e, -e, 1 - e, 1 + e, 1 + e, 2 + e};
Physical Surface("interface") = Surface In BoundingBox{-e, -e, 1 - e, 1 + e, 1 + e, 1 + e};
Physical Surface("bottom") = Surface In BoundingBox{-e, -e, -e, 1 + e, 1 + e, e};
Physical Surface("top") = Surface In BoundingBox{-e, -e, 2 - e, 1 + e, 1 + e, 2 + e};
Physical Surface("x0") = Surface In BoundingBox{-e, -e, -e, e, 1 + e, 2 + e};
Physical Surface("y0") = Surface In BoundingBox{-e, -e, -e, 1 + e, e, 2 + e};
MeshSize{:} = h;
