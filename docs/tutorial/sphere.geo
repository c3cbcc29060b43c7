// An elastic sphere's lower half in the r-z plane (axisymmetric: x = r, y = z), its pole at
// the origin, its centre at (0, R). Mesh size h at the pole, growing to R/10.
DefineConstant[ R = {200.0, Min 1, Name "R"}, h = {1.0, Min 0.1, Name "h"} ];
Point(1) = {0, 0, 0, h};
Point(2) = {0, R, 0, R / 10};
Point(3) = {R, R, 0, R / 10};
Circle(1) = {1, 2, 3};
Line(2) = {3, 2};
Line(3) = {2, 1};
Curve Loop(1) = {1, 2, 3};
Plane Surface(1) = {1};
Field[1] = Distance;
Field[1].PointsList = {1};
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = h;
Field[2].SizeMax = R / 10;
Field[2].DistMin = 10 * h;
Field[2].DistMax = R / 2;
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Physical Surface("body") = {1};
Physical Curve("surface") = {1};
Physical Curve("top") = {2};
