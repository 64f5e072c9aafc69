#!/usr/bin/env python3
"""Run every command a user can run from the ```sh blocks of README.md and docs/*.md, in a
fresh clone of the repository, and fail if one of them fails: the docs cannot drift from
the CLI. Python standard library only.

    python3 scripts/doc_commands.py [--list] [--cli target/release/contactwave]

Commands run in file order, each file in its own fresh `git clone` of HEAD (so that a
command may use the files an earlier one of the same page wrote, as a reader following
the page would), with `contactwave` on PATH being the release binary (`cargo run
--release -p contactwave-cli --` and `./target/release/contactwave` are that binary too).
A command is expected to exit 0. Commands that are not the CLI's (builds, benches, pip,
Python scripts, the test script) and commands with placeholders (`$K`, files a reader is
meant to write) are listed as skipped with their reason (`--list` shows the plan only).
"""

import argparse
import glob
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

#: Prefixes that mean "the contactwave binary".
CLI_PREFIXES = (
    "cargo run --release -p contactwave-cli -- ",
    "./target/release/contactwave ",
    "time ./target/release/contactwave ",
    "contactwave ",
)

#: Why a non-CLI command is not run here (first matching prefix).
SKIP = [
    ("./scripts/test.sh", "the whole test suite (it runs this script)"),
    ("cargo build", "a build (the script uses the built binary)"),
    ("cargo bench", "a benchmark (minutes; docs/performance.md)"),
    ("pip ", "installs packages"),
    ("python", "a Python script (needs the Python package or ../shared)"),
]

#: Files a reader writes themselves before running the command (placeholders).
PLACEHOLDERS = ("$K", "$N", "big.toml", "study.toml")


def blocks(path):
    """Shell lines of the ```sh / ```bash blocks of a Markdown file, continuations
    joined, comments and blank lines dropped."""
    text = Path(path).read_text()
    out = []
    for m in re.finditer(r"```(?:sh|bash|shell)\n(.*?)```", text, re.S):
        joined = m.group(1).replace("\\\n", " ")
        for line in joined.splitlines():
            line = line.strip()
            if line and not line.startswith("#"):
                out.append(" ".join(line.split()))
    return out


def plan(line):
    """("run", command) or ("skip", reason)."""
    for p, why in SKIP:
        if line.startswith(p):
            return "skip", why
    if any(p in line for p in PLACEHOLDERS):
        return "skip", "placeholder: a file or value the reader supplies"
    for p in CLI_PREFIXES:
        if line.startswith(p):
            return "run", "contactwave " + line[len(p):]
    return "skip", "not a contactwave command"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--list", action="store_true", help="show the plan only")
    ap.add_argument("--cli", default=str(ROOT / "target/release/contactwave"))
    args = ap.parse_args()
    files = ["README.md"] + sorted(
        os.path.relpath(p, ROOT) for p in glob.glob(str(ROOT / "docs/*.md"))
    )
    cli = Path(args.cli).resolve()
    if not args.list and not cli.is_file():
        sys.exit(f"error: {cli} not found: cargo build --release -p contactwave-cli")
    failures, ran, skipped = [], 0, 0
    with tempfile.TemporaryDirectory(prefix="contactwave-docs-") as tmp:
        bindir = Path(tmp) / "bin"
        bindir.mkdir()
        (bindir / "contactwave").symlink_to(cli)
        env = dict(os.environ, PATH=f"{bindir}{os.pathsep}{os.environ.get('PATH', '')}")
        for f in files:
            lines = blocks(ROOT / f)
            if not lines:
                continue
            clone = Path(tmp) / f.replace("/", "_")
            if not args.list:
                subprocess.run(["git", "clone", "-q", str(ROOT), str(clone)], check=True)
                (clone / "target/release").mkdir(parents=True)
                (clone / "target/release/contactwave").symlink_to(cli)
            for line in lines:
                kind, what = plan(line)
                if kind == "skip":
                    skipped += 1
                    print(f"skip  {f}: {line}  ({what})")
                    continue
                if args.list:
                    print(f"run   {f}: {what}")
                    continue
                t0 = time.time()
                r = subprocess.run(
                    ["bash", "-c", what], cwd=clone, env=env,
                    stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
                )
                ran += 1
                status = "ok" if r.returncode == 0 else f"FAILED (exit {r.returncode})"
                print(f"{status:<5} {f}: {what}  [{time.time() - t0:.1f} s]")
                if r.returncode != 0:
                    failures.append((f, what, r.stderr.strip().splitlines()[-1:]))
            if not args.list:
                shutil.rmtree(clone, ignore_errors=True)
    if args.list:
        return
    print(f"{ran} commands run, {skipped} skipped, {len(failures)} failed")
    for f, what, err in failures:
        print(f"error: {f}: `{what}`: {' '.join(err)}")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
