// Octant of a thick hollow sphere, inner radius a, outer radius b (Lame problem).
// Physical groups: body, inner, outer, sym_x, sym_y, sym_z.
SetFactory("OpenCASCADE");
DefineConstant[ a = {1.0, Min 1e-6, Name "a"}, b = {2.0, Min 1e-6, Name "b"}, h = {0.25, Min 0.01, Name "h"} ];
Sphere(1) = {0, 0, 0, b, 0, Pi/2, Pi/2};
Sphere(2) = {0, 0, 0, a, 0, Pi/2, Pi/2};
BooleanDifference(3) = { Volume{1}; Delete; }{ Volume{2}; Delete; };
e = 1e-6 * b;
Physical Volume("body") = {3};
Physical Surface("inner") = Surface In BoundingBox{-e, -e, -e, a + e, a + e, a + e};
Physical Surface("sym_x") = Surface In BoundingBox{-e, -e, -e, e, b + e, b + e};
Physical Surface("sym_y") = Surface In BoundingBox{-e, -e, -e, b + e, e, b + e};
Physical Surface("sym_z") = Surface In BoundingBox{-e, -e, -e, b + e, b + e, e};
all() = Surface{:};
outer() = {};
For i In {0 : #all() - 1}
  bb() = BoundingBox Surface{all(i)};
  If (bb(3) > a + e && bb(4) > a + e && bb(5) > a + e)
    outer() += {all(i)};
  EndIf
EndFor
Physical Surface("outer") = {outer()};
MeshSize{:} = h;
