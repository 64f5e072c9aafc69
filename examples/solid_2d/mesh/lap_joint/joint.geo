// Lap joint: two aluminium plates, each 2 mm thick, pressed together over a 10 mm
// overlap. The upper plate spans x 0..40 mm, y 0..2 mm; the lower plate x 30..70 mm,
// y 2..4 mm. The two plates are SEPARATE surfaces that share no point and no curve: over
// the overlap (x 30..40 mm, y = 2 mm) the upper plate's bottom curve and the lower plate's
// top curve are distinct curves with identical geometry, the same direction (+x) and the
// same number of nodes, so that their nodes coincide pairwise (same coordinates,
// different node tags): the contact interface "joint" holds both curves.
//
// Conventions (read by the Rust Gmsh reader): metres; Gmsh x is our x (along the
// plates), Gmsh y is our z, the DEPTH, pointing INTO the specimen: the upper plate's top
// surface is y = 0 and the lower plate lies below it at larger y. The Gmsh GUI draws y
// upward, so there the picture is UPSIDE DOWN (the "upper" plate drawn underneath).
//
// Structured (transfinite) quadrilateral mesh, element size close to h.
//
//   python scripts/mesh.py examples/solid_2d/mesh/lap_joint/joint.geo
//   gmsh -2 -setnumber h 0.25e-3 examples/solid_2d/mesh/lap_joint/joint.geo

DefineConstant[ h = {0.5e-3, Name "h"} ];   // element size, m

Geometry.AutoCoherence = 0;   // keep the coincident points and curves distinct

t = 2e-3;                         // plate thickness, m
x0 = 0; x1 = 30e-3; x2 = 40e-3; x3 = 70e-3;   // upper plate x0..x2, lower x1..x3, overlap x1..x2

ny = Max(1, Round(t / h));            // elements through a plate's thickness
nf = Max(1, Round((x1 - x0) / h));    // along the free part of a plate (30 mm)
nj = Max(1, Round((x2 - x1) / h));    // along the overlap (10 mm)

// Upper plate.
Point(1) = {x0, 0, 0, h};
Point(2) = {x2, 0, 0, h};
Point(3) = {x2, t, 0, h};
Point(4) = {x1, t, 0, h};
Point(5) = {x0, t, 0, h};
Line(1) = {1, 2};   // top surface (free)
Line(2) = {2, 3};   // right end (free)
Line(3) = {4, 3};   // bottom over the overlap (joint), +x
Line(4) = {4, 5};   // bottom, x 0..30 mm (free)
Line(5) = {5, 1};   // left end (wedge)
Curve Loop(1) = {1, 2, -3, 4, 5};
Plane Surface(1) = {1};
Transfinite Curve{1} = nf + nj + 1;
Transfinite Curve{3} = nj + 1;
Transfinite Curve{4} = nf + 1;
Transfinite Curve{2, 5} = ny + 1;
Transfinite Surface{1} = {1, 2, 3, 5};

// Lower plate.
Point(11) = {x1, t, 0, h};
Point(12) = {x2, t, 0, h};
Point(13) = {x3, t, 0, h};
Point(14) = {x3, 2 * t, 0, h};
Point(15) = {x1, 2 * t, 0, h};
Line(11) = {11, 12};   // top over the overlap (joint), +x
Line(12) = {12, 13};   // top, x 40..70 mm (free)
Line(13) = {13, 14};   // right end (end)
Line(14) = {14, 15};   // bottom surface (free)
Line(15) = {15, 11};   // left end (free)
Curve Loop(2) = {11, 12, 13, 14, 15};
Plane Surface(2) = {2};
Transfinite Curve{11} = nj + 1;
Transfinite Curve{12} = nf + 1;
Transfinite Curve{14} = nf + nj + 1;
Transfinite Curve{13, 15} = ny + 1;
Transfinite Surface{2} = {11, 13, 14, 15};

Physical Surface("upper") = {1};
Physical Surface("lower") = {2};
Physical Curve("joint") = {3, 11};
Physical Curve("wedge") = {5};
Physical Curve("end") = {13};
Physical Curve("free") = {1, 2, 4, 12, 14, 15};

Mesh.RecombineAll = 1;
Mesh.ElementOrder = 1;
Mesh.SecondOrderIncomplete = 0;     // order 2: complete 9-node quads
Mesh.MshFileVersion = 4.1;
Mesh.Binary = 0;
Mesh.SaveAll = 0;                   // physical entities only
