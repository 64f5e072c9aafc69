#!/usr/bin/env python3
"""Run every command a user can run from the ```sh blocks of README.md and docs/*.md, in a
fresh clone of the repository, and fail if one of them fails: the docs cannot drift from
the CLI. Python standard library only.

    python3 scripts/doc_commands.py [--list] [--cli target/release/contactwave] [--ran FILE]

Commands run in file order, each file in its own fresh `git clone` of HEAD (so that a
command may use the files an earlier one of the same page wrote, as a reader following
the page would), with `contactwave` on PATH being the release binary (`cargo run
--release -p contactwave-cli --` and `./target/release/contactwave` are that binary too).
A command is expected to exit 0. Commands that are not the CLI's (builds, benches, pip,
Python scripts, the test script) and commands with placeholders (`$K`, files a reader is
meant to write) are listed as skipped with their reason (`--list` shows the plan only).

`contactwave bench` runs at its smallest size (one repetition of each case, 0.1 us of the
2D case): the check is that the command works, not its timings (docs/performance.md).

--ran FILE (written by `scripts/reference_outputs.py check --keep DIR --ran FILE`): a
command that the reference check already ran with the same arguments (apart from `--out`
and `--threads`: outputs are bit-identical for any thread count,
crates/contactwave-cli/tests/all/determinism.rs), at this commit of a clean work tree and
with this binary, and that exited 0 there, is not run again: its output folder is copied
from DIR into the clone (later commands of the page may read it) and it counts as run.
"""

import argparse
import glob
import json
import shlex
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "scripts"))
from reference_outputs import git_state, sha256_file  # noqa: E402  (what --ran records)

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


#: Options of `contactwave bench` set to their smallest useful value.
BENCH_SMALLEST = {"--runs": "1", "--points": "2", "--tribobrake-runs": "1",
                  "--solid-2d-us": "0.1"}


def smallest_bench(what):
    """`contactwave bench ...` with every size option at its smallest (BENCH_SMALLEST)."""
    words = shlex.split(what)
    if words[:2] != ["contactwave", "bench"]:
        return what
    out, i = [], 0
    while i < len(words):
        w = words[i]
        key = w.split("=", 1)[0]
        if key in BENCH_SMALLEST:
            i += 1 if "=" in w else 2
            continue
        out.append(w)
        i += 1
    for k, v in BENCH_SMALLEST.items():
        out += [k, v]
    return shlex.join(out)


def normalized(argv):
    """(argv without `--out X` and `--threads N`, the --out value or None)."""
    key, out, i = [], None, 0
    while i < len(argv):
        w = argv[i]
        name = w.split("=", 1)[0]
        if name in ("--out", "--threads"):
            value = w.split("=", 1)[1] if "=" in w else (argv[i + 1] if i + 1 < len(argv)
                                                          else None)
            if name == "--out":
                out = value
            i += 1 if "=" in w else 2
            continue
        key.append(w)
        i += 1
    return tuple(key), out


def load_reuse(path, cli):
    """{normalized argv: (reference --out folder, seconds)} of the commands that the
    reference check ran and that may stand for the docs' (see --ran), or {} with a note."""
    try:
        doc = json.loads(Path(path).read_text(encoding="utf-8"))
    except (OSError, ValueError) as e:
        print(f"note: {path} not read ({e}): every command runs")
        return {}
    head, _ = git_state()
    if doc.get("commit") != head or not doc.get("clean"):
        print(f"note: {path} is of commit {doc.get('commit')} (clean: {doc.get('clean')}), "
              f"HEAD is {head}: every command runs")
        return {}
    if doc.get("binary_sha256") != sha256_file(cli):
        print(f"note: {path} was made with another binary than {cli}: every command runs")
        return {}
    reuse = {}
    for c in doc.get("commands", []):
        if c.get("exit") == 0:
            key, out = normalized(c["argv"])
            reuse[key] = (out, c.get("seconds", 0.0))
    return reuse


def reusable(what, reuse):
    """(reference --out folder or None, the doc's --out or None, seconds) if `what` was run
    by the reference check, else None. Shell syntax (redirections, pipes) never is."""
    if not reuse or any(ch in what for ch in "<>|;&$`"):
        return None
    words = shlex.split(what)[1:]
    key, out = normalized(words)
    if key not in reuse:
        return None
    ref_out, seconds = reuse[key]
    if (ref_out is None) != (out is None):
        return None
    return ref_out, out, seconds


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--list", action="store_true", help="show the plan only")
    ap.add_argument("--cli", default=str(ROOT / "target/release/contactwave"))
    ap.add_argument("--ran", metavar="FILE",
                    help="the commands the reference check ran (scripts/reference_outputs.py "
                         "--ran): the same ones are not run again")
    args = ap.parse_args()
    files = ["README.md"] + sorted(
        os.path.relpath(p, ROOT) for p in glob.glob(str(ROOT / "docs/*.md"))
    )
    cli = Path(args.cli).resolve()
    if not args.list and not cli.is_file():
        sys.exit(f"error: {cli} not found: cargo build --release -p contactwave-cli")
    failures, ran, skipped, reused = [], 0, 0, 0
    reuse = load_reuse(args.ran, cli) if args.ran and not args.list else {}
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
                what = smallest_bench(what)
                if args.list:
                    print(f"run   {f}: {what}")
                    continue
                hit = reusable(what, reuse)
                if hit is not None:
                    ref_out, out, seconds = hit
                    if ref_out is not None:
                        shutil.copytree(ref_out, clone / out, dirs_exist_ok=True)
                    ran += 1
                    reused += 1
                    print(f"ok    {f}: {what}  [run by the reference check, {seconds:.1f} s]")
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
    print(f"{ran} commands run ({reused} of them by the reference check), {skipped} "
          f"skipped, {len(failures)} failed")
    for f, what, err in failures:
        print(f"error: {f}: `{what}`: {' '.join(err)}")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
