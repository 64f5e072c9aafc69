#!/usr/bin/env python3
"""Check that the library's dependencies resolve to the same features in the two builds
that scripts/test.sh makes of it: the test build of the workspace (contactwave and
contactwave-cli with their dev-dependencies) and maturin's build of crates/contactwave-py
alone (`pip install .`). Equal features mean one release build of the library serves
both; a difference would compile it again (minutes). Prints each package whose features
differ, with both sets, and exits 1; the fix is a feature-alignment dependency in
crates/contactwave-py/Cargo.toml. Standard library only.

    python3 scripts/feature_sets.py
"""

import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def resolve(*args):
    """{(package, version, kind): features} of a `cargo tree` resolution; kind "host" for
    build dependencies and proc-macros and what they pull in, "target" otherwise."""
    out = subprocess.run(
        ["cargo", "tree", "--no-dedupe", "-f", "{p}|{f}", "--prefix", "depth", *args],
        cwd=ROOT, check=True, capture_output=True, text=True).stdout
    result = {}
    host_depth = None  # depth of the proc-macro or build-dependency edge we are under
    for line in out.splitlines():
        if not line.strip():
            continue
        if line.startswith("[build-dependencies]"):
            continue
        i = 0
        while i < len(line) and line[i].isdigit():
            i += 1
        depth, rest = int(line[:i]), line[i:]
        pkg, _, feats = rest.partition("|")
        words = pkg.split()
        name, version = words[0], words[1]
        if host_depth is not None and depth <= host_depth:
            host_depth = None
        if "(proc-macro)" in pkg and host_depth is None:
            host_depth = depth
        kind = "host" if host_depth is not None else "target"
        result.setdefault((name, version, kind), set()).update(
            f for f in feats.split(",") if f)
    return result


def main():
    tests = resolve("-p", "contactwave", "-p", "contactwave-cli", "-e", "normal,dev")
    wheel = resolve("-p", "contactwave-py", "-e", "normal,build")
    lib = resolve("-p", "contactwave", "-e", "normal")
    differ = []
    for key in sorted(lib):
        if key in tests and key in wheel and tests[key] != wheel[key]:
            differ.append((key, tests[key], wheel[key]))
    for (name, version, kind), a, b in differ:
        print(f"{name} {version} ({kind}): test build [{','.join(sorted(a))}], "
              f"wheel [{','.join(sorted(b))}]")
    if differ:
        print(f"error: {len(differ)} dependencies of the library resolve to other features "
              "in the wheel's build than in the test build: `pip install .` would compile "
              "the library again; align them in crates/contactwave-py/Cargo.toml",
              file=sys.stderr)
        return 1
    print(f"the {len(lib)} packages of the library resolve to the same features in the "
          "test build and the wheel's build")
    return 0


if __name__ == "__main__":
    sys.exit(main())
