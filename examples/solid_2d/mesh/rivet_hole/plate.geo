// Plan view of a riveted plate strip, 60 x 30 mm, with a fastener hole of radius 3 mm
// centred at (30, 15) mm and a 2 mm crack growing radially from the hole's rightmost
// point (33, 15) mm to (35, 15) mm. The crack starts on the hole boundary (a point shared
// with the hole's arcs: surface-breaking at the hole) and ends welded inside the plate.
// The left edge is the source aperture: it is in two physical groups, "left" and "wedge".
//
// Conventions (read by the Rust Gmsh reader): metres; Gmsh x is our x, Gmsh y is our z,
// pointing INTO the specimen (here across the strip: y = 0 is the "top" edge, y = 30e-3
// the "bottom" edge). The Gmsh GUI draws y upward, so there the picture is UPSIDE DOWN.
//
// The crack is a curve embedded in the surface (element edges lie along it).
// Unstructured all-quadrilateral mesh; order 2 by default (the hole is curved: the
// mid-side nodes of the hole's edges lie on the circle).
//
//   python scripts/mesh.py examples/solid_2d/mesh/rivet_hole/plate.geo
//   gmsh -2 -order 2 -setnumber h 0.25e-3 examples/solid_2d/mesh/rivet_hole/plate.geo

DefineConstant[ h = {0.6e-3, Name "h"} ];   // element size, m (order 2: ~20 000 nodes)

W = 60e-3;  B = 30e-3;     // strip, m
xo = 30e-3; yo = 15e-3;    // hole centre, m
r = 3e-3;                  // hole radius, m
a = 2e-3;                  // crack length, m

Point(1) = {0, 0, 0, h};
Point(2) = {W, 0, 0, h};
Point(3) = {W, B, 0, h};
Point(4) = {0, B, 0, h};

Point(10) = {xo,     yo,     0, h};   // hole centre (not meshed)
Point(11) = {xo + r, yo,     0, h};   // rightmost point: crack start
Point(12) = {xo,     yo + r, 0, h};
Point(13) = {xo - r, yo,     0, h};
Point(14) = {xo,     yo - r, 0, h};
Point(15) = {xo + r + a, yo, 0, h};   // crack tip

Line(1) = {1, 2};   // top (y = 0)
Line(2) = {2, 3};   // right
Line(3) = {3, 4};   // bottom (y = 30 mm)
Line(4) = {4, 1};   // left

Circle(11) = {11, 10, 12};
Circle(12) = {12, 10, 13};
Circle(13) = {13, 10, 14};
Circle(14) = {14, 10, 11};

Line(20) = {11, 15};   // crack, hole to tip

Curve Loop(1) = {1, 2, 3, 4};
Curve Loop(2) = {11, 12, 13, 14};
Plane Surface(1) = {1, 2};
Curve{20} In Surface{1};

Physical Surface("aluminium") = {1};
Physical Curve("left") = {4};
Physical Curve("wedge") = {4};     // the same curve: the source aperture
Physical Curve("right") = {2};
Physical Curve("top") = {1};
Physical Curve("bottom") = {3};
Physical Curve("hole") = {11, 12, 13, 14};
Physical Curve("crack") = {20};

Mesh.Algorithm = 8;                 // frontal-Delaunay for quads
Mesh.RecombineAll = 1;
Mesh.RecombinationAlgorithm = 3;    // blossom full-quad: no triangle left, size h kept
                                    // (min scaled Jacobian ~0.55; simple full-quad, 2: ~0.36)
Mesh.ElementOrder = 2;
Mesh.SecondOrderIncomplete = 0;     // complete 9-node quads
Mesh.MshFileVersion = 4.1;
Mesh.Binary = 0;
Mesh.SaveAll = 0;                   // physical entities only
