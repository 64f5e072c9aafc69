// Aluminium plate 40 x 10 mm with a 3 mm surface-breaking fatigue crack growing from the
// bottom surface at x = 22 mm, inclined at 45 degrees to the surface toward -x, and a
// source aperture ("wedge", x 4..10 mm) on the top surface.
//
// Conventions (read by the Rust Gmsh reader): metres; Gmsh x is our x (along the
// surface), Gmsh y is our z, the DEPTH, pointing INTO the specimen: the top surface is
// y = 0 and the bottom y = 10e-3. The Gmsh GUI draws y upward, so there the picture is
// UPSIDE DOWN (the top surface at the bottom of the screen, the crack hanging from above).
//
// The crack is a curve embedded in the surface (element edges lie along it), from its
// mouth, a point shared with the two bottom curves, to its tip inside the plate.
// Unstructured all-quadrilateral mesh (frontal-Delaunay for quads + blossom full-quad recombination).
//
//   python scripts/mesh.py examples/solid_2d/mesh/inclined_crack/plate.geo
//   gmsh -2 -setnumber h 0.25e-3 examples/solid_2d/mesh/inclined_crack/plate.geo

DefineConstant[ h = {0.5e-3, Name "h"} ];   // element size, m

W = 40e-3;                 // width, m
T = 10e-3;                 // thickness, m
xw0 = 4e-3;  xw1 = 10e-3;  // source aperture on the top surface, m
xc = 22e-3;                // crack mouth on the bottom surface, m
a = 3e-3;                  // crack length, m
phi = 45 * Pi / 180;       // crack angle to the surface, toward -x

Point(1) = {0,   0, 0, h};
Point(2) = {xw0, 0, 0, h};
Point(3) = {xw1, 0, 0, h};
Point(4) = {W,   0, 0, h};
Point(5) = {W,   T, 0, h};
Point(6) = {xc,  T, 0, h};                                // crack mouth
Point(7) = {0,   T, 0, h};
Point(8) = {xc - a * Cos(phi), T - a * Sin(phi), 0, h};  // crack tip

Line(1) = {1, 2};   // top, x 0..4 mm
Line(2) = {2, 3};   // top, the source aperture
Line(3) = {3, 4};   // top, x 10..40 mm
Line(4) = {4, 5};   // right
Line(5) = {5, 6};   // bottom, right of the crack mouth
Line(6) = {6, 7};   // bottom, left of the crack mouth
Line(7) = {7, 1};   // left
Line(8) = {6, 8};   // crack, mouth to tip

Curve Loop(1) = {1, 2, 3, 4, 5, 6, 7};
Plane Surface(1) = {1};
Curve{8} In Surface{1};

Physical Surface("aluminium") = {1};
Physical Curve("top") = {1, 3};
Physical Curve("wedge") = {2};
Physical Curve("bottom") = {5, 6};
Physical Curve("left") = {7};
Physical Curve("right") = {4};
Physical Curve("crack") = {8};

Mesh.Algorithm = 8;                 // frontal-Delaunay for quads
Mesh.RecombineAll = 1;
Mesh.RecombinationAlgorithm = 3;    // blossom full-quad: no triangle left, size h kept
                                    // (min scaled Jacobian ~0.55; simple full-quad, 2: ~0.36)
Mesh.ElementOrder = 1;
Mesh.SecondOrderIncomplete = 0;     // order 2: complete 9-node quads
Mesh.MshFileVersion = 4.1;
Mesh.Binary = 0;
Mesh.SaveAll = 0;                   // physical entities only
