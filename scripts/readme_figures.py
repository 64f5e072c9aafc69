#!/usr/bin/env python3
"""Regenerate the README's figures (docs/figures/*.svg) from `contactwave reproduce`, so that
they cannot drift from the report: each is copied byte for byte from the figures/ folder that
`reproduce` writes. Python standard library only.

    python3 scripts/readme_figures.py [--check] [--bin target/release/contactwave]

--check compares instead of copying and exits 1 naming every figure that differs (the Rust
test `readme_figures_are_what_reproduce_draws` in crates/contactwave/tests/all/reproduce.rs makes
the same check in `cargo test`). Build the CLI first: cargo build --release -p contactwave-cli
"""

import argparse
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

#: The README's figures: file stem in docs/figures/ (= the report's figure id) and the
#: chapter of `reproduce` that draws it.
FIGURES = {
    "ch3_fig32_stiffness_xi": "chapter3",
    "ch4_fig69_71_73_trends": "chapter4",
}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--check", action="store_true", help="compare, do not write")
    ap.add_argument("--bin", default=str(ROOT / "target/release/contactwave"))
    args = ap.parse_args()
    differ = []
    with tempfile.TemporaryDirectory() as tmp:
        for chapter in sorted(set(FIGURES.values())):
            out = Path(tmp) / chapter
            subprocess.run(
                [args.bin, "reproduce", chapter, "--out", str(out)],
                check=True,
                stdout=subprocess.DEVNULL,
            )
        for stem, chapter in FIGURES.items():
            new = (Path(tmp) / chapter / "figures" / f"{stem}.svg").read_bytes()
            dest = ROOT / "docs/figures" / f"{stem}.svg"
            if args.check:
                if not dest.is_file() or dest.read_bytes() != new:
                    differ.append(str(dest.relative_to(ROOT)))
            else:
                dest.write_bytes(new)
                print(f"wrote {dest.relative_to(ROOT)}")
    if differ:
        for d in differ:
            print(f"{d}: differs from what `contactwave reproduce` draws "
                  "(run python3 scripts/readme_figures.py)", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
