// Hemisphere R = 1000 nm, pole (top point) at z = 0, body in -1000 <= z <= 0.
// Units: nanometres.  gmsh 4.8.4 (Debian), OpenCASCADE kernel.
// Copy of ../shared/bench/calculix-hemisphere/hemisphere.geo with the mesh sizes as parameters.
//
// Two volumes, glued conformally (Coherence):
//   volume "cap"  : latitude phic..90 deg   (spherical cap, base radius rc = 150 nm, height 11.314 nm)
//   volume "zone" : latitude 0..phic        (rest of the hemisphere)
// Physical groups:
//   Volume  "body"   = both volumes                 (10-node tetrahedra)
//   Surface "top"    = spherical cap, rho <= 150 nm (contact surface)
//   Surface "side"   = rest of the spherical surface (free)
//   Surface "bottom" = flat disk z = -1000 nm       (fixed)
SetFactory("OpenCASCADE");
General.NumThreads = 1;

R    = 1000;          // sphere radius
rc   = 150;           // base radius of the "top" cap
phic = Acos(rc/R);    // latitude of the cap boundary

Sphere(1) = {0, 0, -R, R, 0,    phic, 2*Pi};   // zone
Sphere(2) = {0, 0, -R, R, phic, Pi/2, 2*Pi};   // cap
Coherence;

// Mesh size: h = min(HMAX, H0 + G * dist), dist = distance to the fine disk
// {depth below the sphere surface = 0, rho <= RHO0}, approximated by
// sqrt(depth^2 + max(0, rho - RHO0)^2), depth = R - |x - centre|.
// (parameters: `--set mesh.parameters.H0=...` scales the mesh for the scaling study)
DefineConstant[ H0 = {3.5, Min 0.5, Name "H0"}, G = {0.4, Min 0, Name "G"}, RHO0 = {75, Min 0, Name "RHO0"}, HMAX = {150, Min 1, Name "HMAX"} ];
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Field[1] = MathEval;
Field[1].F = Sprintf("min(%g, %g + %g*sqrt((%g - sqrt(x*x + y*y + (z + %g)*(z + %g)))^2 + max(0, sqrt(x*x + y*y) - %g)^2))",
                     HMAX, H0, G, R, R, R, RHO0);
Background Field = 1;

Mesh.Algorithm   = 6;    // Frontal-Delaunay 2D
Mesh.Algorithm3D = 1;    // Delaunay 3D
Mesh.ElementOrder = 2;   // 10-node tetrahedra, midside nodes on the curved boundary
Mesh.MshFileVersion = 4.1;

// classify the 4 OCC surfaces by bounding box (the 4th one is the internal cap/zone interface)
all[] = Surface{:};
top[] = {};  side[] = {};  bottom[] = {};
For i In {0:#all[]-1}
  bb[] = BoundingBox Surface{all[i]};      // xmin ymin zmin xmax ymax zmax
  If (bb[5] < -R + 1)
    bottom[] += all[i];                    // flat disk z = -R
  ElseIf (bb[5] > -1 && bb[3] - bb[0] < 2*rc + 10)
    top[] += all[i];                       // spherical cap reaching the pole
  ElseIf (bb[3] - bb[0] > 2*rc + 10)
    side[] += all[i];                      // spherical zone
  EndIf
EndFor
If (#top[] != 1 || #side[] != 1 || #bottom[] != 1)
  Error("surface classification failed");
EndIf

Physical Volume("body")    = {1, 2};
Physical Surface("top")    = {top[]};
Physical Surface("side")   = {side[]};
Physical Surface("bottom") = {bottom[]};
