// Thick hollow sphere in the r-z half plane (x = r, y = z), quarter annulus a <= rho <= b.
// Physical groups: body, inner, outer, sym_z (z = 0 plane), axis (r = 0).
DefineConstant[ a = {1.0, Min 1e-6, Name "a"}, b = {2.0, Min 1e-6, Name "b"}, h = {0.1, Min 0.002, Name "h"} ];
Point(1) = {0, 0, 0, h};
Point(2) = {a, 0, 0, h};
Point(3) = {b, 0, 0, h};
Point(4) = {0, a, 0, h};
Point(5) = {0, b, 0, h};
Line(1) = {2, 3};
Circle(2) = {3, 1, 5};
Line(3) = {5, 4};
Circle(4) = {4, 1, 2};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Surface("body") = {1};
Physical Curve("inner") = {4};
Physical Curve("outer") = {2};
Physical Curve("sym_z") = {1};
Physical Curve("axis") = {3};
