// Two solid cylinders of radius 1 and length 1 stacked along the axis, in the r-z half plane
// (x = r, y = z), joined at z = 1 ("interface"). Groups: lower, upper, interface, bottom
// (z = 0), top (z = 2).
DefineConstant[ h = {0.5, Min 0.005, Name "h"} ];
Point(1) = {0, 0, 0, h};
Point(2) = {1, 0, 0, h};
Point(3) = {1, 1, 0, h};
Point(4) = {0, 1, 0, h};
Point(5) = {1, 2, 0, h};
Point(6) = {0, 2, 0, h};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Line(5) = {3, 5};
Line(6) = {5, 6};
Line(7) = {6, 4};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Curve Loop(2) = {-3, 5, 6, 7};
Plane Surface(2) = {2};
Physical Surface("lower") = {1};
Physical Surface("upper") = {2};
Physical Curve("interface") = {3};
Physical Curve("bottom") = {1};
Physical Curve("top") = {6};
