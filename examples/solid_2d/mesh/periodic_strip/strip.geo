// A periodic aluminium strip 2 mm wide and 32 mm deep, sheared: each depth z shifted
// along x by `shear` z, so that every element is a parallelogram (general, not a
// rectangle), with a full-width interface at z = 16 mm (the 1D reduction of
// examples/solid_2d/interface_reduction.toml on a skewed mesh). The two slanted sides are
// periodic: "right" is "left" moved by the width along x.
//
// Conventions (read by the Rust Gmsh reader): metres; Gmsh x is our x, Gmsh y is our z,
// the DEPTH: the top surface is y = 0 and the bottom y = 32e-3 (upside down in the GUI).
//
//   python scripts/mesh.py examples/solid_2d/mesh/periodic_strip/strip.geo
//   gmsh -2 -setnumber h 0.125e-3 examples/solid_2d/mesh/periodic_strip/strip.geo

DefineConstant[ h = {0.25e-3, Name "h"} ];        // element size, m
DefineConstant[ shear = {0.3, Name "shear"} ];    // x shift per metre of depth

w = 2e-3;                  // width, m
zs[] = {0, 16e-3, 32e-3};  // top, interface, bottom, m

For j In {0 : 2}
  Point(100 + j) = {shear * zs[j], zs[j], 0, h};
  Point(200 + j) = {shear * zs[j] + w, zs[j], 0, h};
  Line(1000 + j) = {100 + j, 200 + j};                        // across, at depth j
  Transfinite Curve{1000 + j} = Round(w / h) + 1;
EndFor
For j In {0 : 1}
  Line(2000 + j) = {100 + j, 100 + j + 1};                    // left side
  Line(3000 + j) = {200 + j, 200 + j + 1};                    // right side
  n = Round((zs[j + 1] - zs[j]) / h) + 1;
  Transfinite Curve{2000 + j, 3000 + j} = n;
  Periodic Curve{3000 + j} = {2000 + j} Translate{w, 0, 0};
  Curve Loop(4000 + j) = {1000 + j, 3000 + j, -(1000 + j + 1), -(2000 + j)};
  Plane Surface(4000 + j) = {4000 + j};
  Transfinite Surface{4000 + j};
EndFor

Physical Surface("aluminium") = {4000, 4001};
Physical Curve("top") = {1000};
Physical Curve("interface") = {1001};
Physical Curve("bottom") = {1002};
Physical Curve("left") = {2000, 2001};
Physical Curve("right") = {3000, 3001};

Mesh.RecombineAll = 1;
Mesh.ElementOrder = 1;
Mesh.SecondOrderIncomplete = 0;     // order 2: complete 9-node quads
Mesh.MshFileVersion = 4.1;
Mesh.Binary = 0;
Mesh.SaveAll = 0;                   // physical entities only
