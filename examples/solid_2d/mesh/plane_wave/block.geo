// Aluminium block 24 x 12 mm with a closed 3 mm crack inside it, at 45 degrees to the
// surface, centred at (12, 7) mm, inside a closed curve "tfsf" (the rectangle x 3..21 mm,
// z 2..10 mm) across which a plane wave is injected: the total field inside it, the
// scattered field alone outside.
//
// Conventions (read by the Rust Gmsh reader): metres; Gmsh x is our x (along the
// surface), Gmsh y is our z, the DEPTH, pointing INTO the specimen: the top surface is
// y = 0 and the bottom y = 12e-3 (the Gmsh GUI draws the block upside down).
//
// Two surfaces share the box (so that element edges lie along it); the crack is a curve
// embedded in the inner one, both tips welded. The left, right and bottom sides are
// straight sides on the bounding box: the scenario frames them with PML.
// Unstructured all-quadrilateral mesh (frontal-Delaunay for quads + blossom recombination).
//
//   python scripts/mesh.py examples/solid_2d/mesh/plane_wave/block.geo

DefineConstant[ h = {0.5e-3, Name "h"} ];   // element size, m

W = 24e-3;                 // width, m
T = 12e-3;                 // depth, m
x0 = 3e-3;  x1 = 21e-3;    // the box along x, m
z0 = 2e-3;  z1 = 10e-3;    // the box in depth, m
xc = 12e-3;  zc = 7e-3;    // crack centre, m
a = 3e-3;                  // crack length, m
phi = 45 * Pi / 180;       // crack angle to the surface

Point(1) = {0, 0, 0, h};
Point(2) = {W, 0, 0, h};
Point(3) = {W, T, 0, h};
Point(4) = {0, T, 0, h};
Point(5) = {x0, z0, 0, h};
Point(6) = {x1, z0, 0, h};
Point(7) = {x1, z1, 0, h};
Point(8) = {x0, z1, 0, h};
Point(9) = {xc - 0.5 * a * Cos(phi), zc - 0.5 * a * Sin(phi), 0, h};  // crack ends
Point(10) = {xc + 0.5 * a * Cos(phi), zc + 0.5 * a * Sin(phi), 0, h};

Line(1) = {1, 2};   // top
Line(2) = {2, 3};   // right
Line(3) = {3, 4};   // bottom
Line(4) = {4, 1};   // left
Line(5) = {5, 6};   // the box
Line(6) = {6, 7};
Line(7) = {7, 8};
Line(8) = {8, 5};
Line(9) = {9, 10};  // crack

Curve Loop(1) = {1, 2, 3, 4};
Curve Loop(2) = {5, 6, 7, 8};
Plane Surface(1) = {1, 2};   // the block outside the box
Plane Surface(2) = {2};      // inside the box
Curve{9} In Surface{2};

Physical Surface("aluminium") = {1, 2};
Physical Curve("top") = {1};
Physical Curve("tfsf") = {5, 6, 7, 8};
Physical Curve("left") = {4};
Physical Curve("right") = {2};
Physical Curve("bottom") = {3};
Physical Curve("crack") = {9};

Mesh.Algorithm = 8;                 // frontal-Delaunay for quads
Mesh.RecombineAll = 1;
Mesh.RecombinationAlgorithm = 3;    // blossom full-quad: no triangle left
Mesh.ElementOrder = 1;
Mesh.SecondOrderIncomplete = 0;     // order 2: complete 9-node quads
Mesh.MshFileVersion = 4.1;
Mesh.Binary = 0;
Mesh.SaveAll = 0;                   // physical entities only
