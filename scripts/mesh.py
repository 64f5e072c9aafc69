#!/usr/bin/env python3
"""Mesh the Gmsh geometries of the 2D solver: quadrilaterals only, MSH 4.1 ASCII.

    python scripts/mesh.py [--order N] [--set name=value ...] [--out DIR] GEO...
    python scripts/mesh.py --all

Each .geo is meshed in 2D with the gmsh Python API (`pip install gmsh`) and written as
`<geo stem>.msh` beside it (or in --out). `--set name=value` gives a parameter of the .geo
(a DefineConstant, e.g. h=0.25e-3 or theta=30) its value before the file is read;
`--order` sets Mesh.ElementOrder (1 or 2, complete 9-node quads; default: the .geo's
own). One line is printed per file: path, nodes, quads, order, physical groups as
name(dimension). A mesh with a triangle left is refused: nothing is written, one line
names the file and the exit status is 2.

`--all` regenerates every committed example mesh under examples/solid_2d/mesh, each with
its own default order, the rotated plate at theta = 0, 30 and 45 degrees (plate_0.msh,
plate_30.msh, plate_45.msh).
"""

import argparse
import sys
from pathlib import Path

import gmsh

ROOT = Path(__file__).resolve().parents[1]
MESH = ROOT / "examples" / "solid_2d" / "mesh"

# (geometry, parameters, output name) of every committed mesh.
ALL = [
    (MESH / "inclined_crack" / "plate.geo", {}, "plate.msh"),
    (MESH / "rivet_hole" / "plate.geo", {}, "plate.msh"),
    (MESH / "lap_joint" / "joint.geo", {}, "joint.msh"),
    (MESH / "curved_delamination" / "shell.geo", {}, "shell.msh"),
    (MESH / "periodic_strip" / "strip.geo", {}, "strip.msh"),
    (MESH / "plane_wave" / "block.geo", {}, "block.msh"),
] + [
    (MESH / "rotated" / "plate.geo", {"theta": float(t)}, f"plate_{t}.msh")
    for t in (0, 30, 45)
]


class Refused(Exception):
    """A mesh that is not all quadrilaterals."""


def mesh(geo, params, out, order=None):
    """Mesh `geo` with `params` and write `out`; return the summary line."""
    gmsh.initialize()
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        for name, value in params.items():
            gmsh.onelab.setNumber(name, [value])  # read by DefineConstant
            gmsh.parser.setNumber(name, [value])  # read by If(!Exists(name))
        gmsh.open(str(geo))
        if order is not None:
            gmsh.option.setNumber("Mesh.ElementOrder", order)
        order = int(gmsh.option.getNumber("Mesh.ElementOrder"))
        gmsh.option.setNumber("Mesh.SecondOrderIncomplete", 0)
        gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
        gmsh.option.setNumber("Mesh.Binary", 0)
        gmsh.option.setNumber("Mesh.SaveAll", 0)
        gmsh.model.mesh.generate(2)

        quads = 0
        types, tags, _ = gmsh.model.mesh.getElements(2)
        for etype, etags in zip(types, tags):
            name, _, _, _, _, corners = gmsh.model.mesh.getElementProperties(etype)
            if corners != 4:
                raise Refused(f"{geo}: {len(etags)} {name} elements left, quadrilaterals only")
            quads += len(etags)

        gmsh.write(str(out))
        groups = " ".join(
            f"{gmsh.model.getPhysicalName(dim, tag)}({dim})"
            for dim, tag in gmsh.model.getPhysicalGroups()
        )
    finally:
        gmsh.finalize()
    return f"{shown(out)}: {written_nodes(out)} nodes, {quads} quads, order {order}, {groups}"


def written_nodes(msh):
    """The number of nodes in the $Nodes section of an MSH 4.1 ASCII file."""
    with open(msh) as f:
        for line in f:
            if line.strip() == "$Nodes":
                return int(next(f).split()[1])
    raise ValueError(f"{msh}: no $Nodes section")


def shown(path):
    path = path.resolve()
    return path.relative_to(Path.cwd()) if path.is_relative_to(Path.cwd()) else path


def parameter(text):
    name, sep, value = text.partition("=")
    if not sep or not name:
        raise argparse.ArgumentTypeError(f"expected name=value, got {text!r}")
    return name, float(value)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("geo", nargs="*", type=Path, help=".geo files to mesh")
    ap.add_argument("--order", type=int, choices=(1, 2), help="element order (default: the .geo's)")
    ap.add_argument("--set", type=parameter, action="append", default=[], metavar="NAME=VALUE",
                    help="set a .geo parameter, e.g. h=0.25e-3 (repeatable)")
    ap.add_argument("--out", type=Path, help="output folder (default: beside each .geo)")
    ap.add_argument("--all", action="store_true", help="regenerate every committed example mesh")
    args = ap.parse_args()
    if args.all == bool(args.geo):
        ap.error("give either GEO files or --all")
    if args.all and (args.order or args.set or args.out):
        ap.error("--all uses each mesh's own order and parameters, beside its .geo")

    if args.all:
        jobs = [(geo, params, geo.parent / name) for geo, params, name in ALL]
    else:
        if args.out:
            args.out.mkdir(parents=True, exist_ok=True)
        params = dict(args.set)
        jobs = [(geo, params, (args.out or geo.parent) / f"{geo.stem}.msh") for geo in args.geo]

    for geo, params, out in jobs:
        if not geo.is_file():
            sys.exit(f"{geo}: no such file")
        try:
            print(mesh(geo, params, out, None if args.all else args.order), flush=True)
        except Refused as refused:
            print(refused, file=sys.stderr)
            sys.exit(2)


if __name__ == "__main__":
    main()
