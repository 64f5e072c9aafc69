// Curved composite shell: a ring sector of inner radius 50 mm and outer radius 54 mm
// (4 mm thick) spanning 40 degrees, centred on (30, 60) mm and symmetric about x = 30 mm,
// so that the outer surface's apex is at (30, 6) mm: the convex outer surface faces
// y = 0 (the top). A delamination at mid-thickness (radius 52 mm) spans 8 degrees around
// the apex; the source aperture "wedge" is an arc of the outer surface spanning 6 degrees,
// centred 12 degrees from the apex on the -x side (angles -15..-9 degrees).
//
// Angles phi are measured from the apex, positive toward +x: a point at radius R is
// (xo + R sin(phi), yo - R cos(phi)).
//
// Conventions (read by the Rust Gmsh reader): metres; Gmsh x is our x, Gmsh y is our z,
// the DEPTH, pointing INTO the specimen (downward). The Gmsh GUI draws y upward, so there
// the picture is UPSIDE DOWN (the shell appears as a bowl, apex at the bottom).
//
// Structured (transfinite) quadrilateral mesh: the sector is split into 5 angular x 2
// radial blocks whose edges follow the delamination (the arc between two blocks at
// radius 52 mm, -4..4 degrees: element edges lie along it, its ends are block corners)
// and the ends of the wedge. Order 2 by default: the mid-side nodes lie on the arcs.
//
//   python scripts/mesh.py examples/solid_2d/mesh/curved_delamination/shell.geo
//   gmsh -2 -order 2 -setnumber h 0.25e-3 examples/solid_2d/mesh/curved_delamination/shell.geo

DefineConstant[ h = {0.5e-3, Name "h"} ];   // element size, m

xo = 30e-3; yo = 60e-3;                  // centre of curvature, m
Rs[] = {50e-3, 52e-3, 54e-3};            // inner, delamination (mid-thickness), outer, m
phis[] = {-20, -15, -9, -4, 4, 20};      // block edges, degrees: ends, wedge, delamination
NA = #phis[] - 1;                        // angular blocks
NR = #Rs[] - 1;                          // radial blocks

Point(1) = {xo, yo, 0, h};               // centre of curvature (not meshed)
For i In {0 : NA}
  For j In {0 : NR}
    Point(100 + 10 * i + j) = {xo + Rs[j] * Sin(phis[i] * Pi / 180),
                               yo - Rs[j] * Cos(phis[i] * Pi / 180), 0, h};
  EndFor
EndFor

// Arcs 1000 + 10 i + j: radius j, from angle i to i + 1.
For i In {0 : NA - 1}
  n = Max(1, Round(Rs[1] * (phis[i + 1] - phis[i]) * Pi / 180 / h));
  For j In {0 : NR}
    Circle(1000 + 10 * i + j) = {100 + 10 * i + j, 1, 100 + 10 * (i + 1) + j};
    Transfinite Curve{1000 + 10 * i + j} = n + 1;
  EndFor
EndFor
// Radial lines 2000 + 10 i + j: angle i, from radius j to j + 1.
For i In {0 : NA}
  For j In {0 : NR - 1}
    Line(2000 + 10 * i + j) = {100 + 10 * i + j, 100 + 10 * i + j + 1};
    Transfinite Curve{2000 + 10 * i + j} = Max(1, Round((Rs[j + 1] - Rs[j]) / h)) + 1;
  EndFor
EndFor
// Blocks 3000 + 10 i + j, counter-clockwise in Gmsh's (x, y), as the other examples.
blocks[] = {};
For i In {0 : NA - 1}
  For j In {0 : NR - 1}
    Curve Loop(3000 + 10 * i + j) = {2000 + 10 * i + j, 1000 + 10 * i + j + 1,
                                     -(2000 + 10 * (i + 1) + j), -(1000 + 10 * i + j)};
    Plane Surface(3000 + 10 * i + j) = {3000 + 10 * i + j};
    Transfinite Surface{3000 + 10 * i + j};
    blocks[] += {3000 + 10 * i + j};
  EndFor
EndFor

Physical Surface("composite") = {blocks[]};
Physical Curve("inner") = {1000, 1010, 1020, 1030, 1040};
Physical Curve("outer") = {1002, 1022, 1032, 1042};
Physical Curve("wedge") = {1012};                       // outer, -15..-9 degrees
Physical Curve("ends") = {2000, 2001, 2050, 2051};      // radial ends, -20 and +20 degrees
Physical Curve("delamination") = {1031};                // radius 52 mm, -4..4 degrees

Mesh.RecombineAll = 1;
Mesh.ElementOrder = 2;
Mesh.SecondOrderIncomplete = 0;     // complete 9-node quads
Mesh.MshFileVersion = 4.1;
Mesh.Binary = 0;
Mesh.SaveAll = 0;                   // physical entities only
