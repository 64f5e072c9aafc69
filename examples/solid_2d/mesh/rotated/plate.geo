// The 2D reference plate (examples/solid_2d/plate_crack.toml): aluminium, 40 x 10 mm,
// with a 2 mm horizontal crack from (19, 5) mm to (21, 5) mm and a source aperture
// "wedge" x 8..12 mm on the top surface, the whole specimen rotated by `theta` degrees
// about the origin (the top-left corner): positive theta turns +x toward +y (into the
// depth). The points are rotated before the curves are built.
//
// Conventions (read by the Rust Gmsh reader): metres; Gmsh x is our x (along the
// surface), Gmsh y is our z, the DEPTH, pointing INTO the specimen: at theta = 0 the top
// surface is y = 0 and the bottom y = 10e-3. The Gmsh GUI draws y upward, so there the
// picture is UPSIDE DOWN: a positive theta is a counter-clockwise turn in the GUI and a
// clockwise turn in the specimen's own picture (depth downward).
//
// Structured (transfinite) mesh aligned with the plate: 5 x 2 blocks split at x = 8, 12,
// 19, 21 mm and at mid-depth, so the crack is the edge between two blocks (its ends are
// block corners) and at theta = 0 the elements are axis-aligned rectangles close to h.
//
//   python scripts/mesh.py --set theta=30 examples/solid_2d/mesh/rotated/plate.geo
//   gmsh -2 -setnumber theta 30 -setnumber h 0.25e-3 examples/solid_2d/mesh/rotated/plate.geo

DefineConstant[ h = {0.5e-3, Name "h"} ];      // element size, m
DefineConstant[ theta = {0, Name "theta"} ];   // rotation about the origin, degrees

xs[] = {0, 8e-3, 12e-3, 19e-3, 21e-3, 40e-3};  // block edges along the plate, m
ys[] = {0, 5e-3, 10e-3};                       // block edges through the depth, m
NX = #xs[] - 1;
NY = #ys[] - 1;
c = Cos(theta * Pi / 180);
s = Sin(theta * Pi / 180);

For i In {0 : NX}
  For j In {0 : NY}
    Point(100 + 10 * i + j) = {c * xs[i] - s * ys[j], s * xs[i] + c * ys[j], 0, h};
  EndFor
EndFor
// Lines along the plate 1000 + 10 i + j: depth j, from x i to i + 1.
For i In {0 : NX - 1}
  For j In {0 : NY}
    Line(1000 + 10 * i + j) = {100 + 10 * i + j, 100 + 10 * (i + 1) + j};
    Transfinite Curve{1000 + 10 * i + j} = Max(1, Round((xs[i + 1] - xs[i]) / h)) + 1;
  EndFor
EndFor
// Lines through the depth 2000 + 10 i + j: x i, from depth j to j + 1.
For i In {0 : NX}
  For j In {0 : NY - 1}
    Line(2000 + 10 * i + j) = {100 + 10 * i + j, 100 + 10 * i + j + 1};
    Transfinite Curve{2000 + 10 * i + j} = Max(1, Round((ys[j + 1] - ys[j]) / h)) + 1;
  EndFor
EndFor
// Blocks 3000 + 10 i + j.
blocks[] = {};
For i In {0 : NX - 1}
  For j In {0 : NY - 1}
    Curve Loop(3000 + 10 * i + j) = {1000 + 10 * i + j, 2000 + 10 * (i + 1) + j,
                                     -(1000 + 10 * i + j + 1), -(2000 + 10 * i + j)};
    Plane Surface(3000 + 10 * i + j) = {3000 + 10 * i + j};
    Transfinite Surface{3000 + 10 * i + j};
    blocks[] += {3000 + 10 * i + j};
  EndFor
EndFor

Physical Surface("aluminium") = {blocks[]};
Physical Curve("top") = {1000, 1020, 1030, 1040};     // the wedge's neighbours
Physical Curve("wedge") = {1010};                     // x 8..12 mm on the top surface
Physical Curve("bottom") = {1002, 1012, 1022, 1032, 1042};
Physical Curve("left") = {2000, 2001};
Physical Curve("right") = {2050, 2051};
Physical Curve("crack") = {1031};                     // y = 5 mm, x 19..21 mm

Mesh.RecombineAll = 1;
Mesh.ElementOrder = 1;
Mesh.SecondOrderIncomplete = 0;     // order 2: complete 9-node quads
Mesh.MshFileVersion = 4.1;
Mesh.Binary = 0;
Mesh.SaveAll = 0;                   // physical entities only
