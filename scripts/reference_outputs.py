#!/usr/bin/env python3
"""Reference-output check: every value that the `contactwave` CLI writes stays what it was.

    python3 scripts/reference_outputs.py record|check [--bin PATH] [--ref FILE] [--keep DIR]
                                                      [--ran FILE] [--all]

`record` runs the commands below into a temporary folder (or --keep DIR), stores every output
file's values (tests/reference/outputs.json and tests/reference/values/, see below) and
prints every value that changed against the references it replaces (file, column and row or
key, old, new, relative change): the list a re-recording commit must explain. `check` runs
the same commands and compares: one line per differing value (the first 20 per file; --all:
every one), then `N passed, M failed` (N, M = numbers of files; a command's stdout counts as
a file); exit code 1 on any failure. Both also assert FINDINGS below on the outputs (physics
that a value-for-value comparison cannot tell, e.g. that the 2D identification recovers the
values its data were made with); `record` stores nothing when one fails. Standard library only; run from anywhere (commands run
in the repository root, so input paths written into outputs, such as summary.json's
"scenario", are relative).

Commands (commands() below; two at a time, AFTER the dependencies, the longest first: about
5 minutes on 2 cores, most of it reproduce, validate and the 2D identification):
  reproduce all; run, law and sweep on every file of examples/shear/; run on every
  scenario of examples/*.toml (files with a top-level `base =`
  or an `[[axis]]` table are sweeps) and of examples/solid_2d/; sweep --threads 2 on every
  sweep of examples/ and on examples/sweeps/*_quick.toml;
  sweep --shard 1/2 and 2/2 of examples/stiffness_xi_grid.toml, then merge; law on every
  half-space scenario of examples/ and examples/thesis/ (law refuses bar stacks);
  convergence examples/rccm_1.6MPa.toml;
  identify on every examples/identify/*.toml except tribobrake_power_law.toml (about 2 400
  bar-stack forward runs, several minutes: skipped), identify --design and
  identify --synthesize (seeded) of rccm_undamaged.toml; fit power-law (text and --json,
  both stiffness columns of examples/thesis/table2_contact_stiffness.csv, the copy of
  ../shared/data/table2_contact_stiffness.csv, and its default columns); validate.
  Not covered: `bench` (its output is nothing but timings) and `sweep --resume` (the same
  rows as a fresh sweep).

What is stored (format 2; tests/reference/README.md):
  CSV: header and row count exactly; every cell of every numeric column (empty cells, NaN
    and infinities exactly); a column with any non-number cell is text: its cells by sha256.
    Rows of the files in SORTED_CSV (written in completion order by parallel runs) are
    sorted by their first column (the point index) first.
  JSON: every leaf under a dotted key (list items by index): numbers as values, strings,
    booleans and null exactly.
  stdout: the text lines, with the exit code.
  SVG, HTML: the text with its numbers taken out (sha256), and the numbers as printed.
  anything else (.hash, .shard): sha256 of the content.
  Small files are stored inline in outputs.json (readable, numbers in full precision). The
  numbers of a file with more than INLINE_MAX of them go to values/<file>.xz: CSV values as
  the upper 46 bits of each IEEE double (sign, exponent, 35 mantissa bits, rounded: relative
  error below 1.5e-11), second differences of the integers, zigzag, 7 byte planes per
  column, xz; SVG/HTML numbers as their printed text, one per line, xz. outputs.json keeps
  each column's count, min and max readable, so a re-recording shows in `git diff`.

When two numbers agree (tolerance(), TEXT_TOLERANCE):
  CSV and JSON values: |a - b| <= REL_TOL max(|a|, |b|) + floor, REL_TOL = 1e-9. The floor
    is the largest of
    - COLUMN_FLOOR (1e-12) times the largest |value| of the reference column (CSV) or list
      (JSON keys with list indices, grouped with the indices replaced by *): a value near a
      zero crossing of a time series is known only to the round-off of the column's scale;
    - ROUNDOFF_FLOORS, by name (column or JSON key): absolute floors for quantities that are
      pure round-off at some points: relative error measures and energy-closure errors,
      harmonic ratios that are zero by symmetry, energies and slips that are zero by physics.
  Numbers in text (stdout, SVG, HTML) are rounded for display: they agree within REL_TOL,
    or within one unit in the last printed digit (a number printed with a fraction or an
    exponent), or below TEXT_FLOOR (1e-11) in magnitude; integers exactly on stdout (counts)
    and within 1 in SVG and HTML (pixel coordinates rounded from floats).

Non-deterministic content, excluded by name (found by recording twice and diffing, and by
looking for dates, versions and temporary paths): see NONDETERMINISTIC_* below.
"""

import argparse
import array
import csv
import fnmatch
import hashlib
import json
import lzma
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
FORMAT = 2
REL_TOL = 1e-9
COLUMN_FLOOR = 1e-12
TEXT_FLOOR = 1e-11
# Absolute floors by name (regex, case-insensitive, searched in the CSV column name or the
# JSON key; the first match applies): (regex, floor in the quantity's SI unit, why)
ROUNDOFF_FLOORS = [
    (r"(error|residual).*percent", 1e-10,
     "relative errors in percent (convergence.csv): 1e-12 as a fraction"),
    (r"error|residual", 1e-12,
     "relative error measures and energy-closure errors (dimensionless; a closure error of "
     "1e-15 is round-off of energies of order 1)"),
    (r"(^|[._])a\d|harmonic|_over_", 1e-12,
     "harmonic amplitudes over the incident or the fundamental amplitude (dimensionless): "
     "even harmonics of symmetric responses are zero by symmetry (1e-17 computed)"),
    (r"energy|dissipation", 1e-15,
     "energies per unit area (J/m^2; incident energies 1e-3 to 10): the stored energy at the "
     "end and the shear energy reflected by a bonded interface are zero by physics"),
    (r"slip", 1e-18,
     "slips (m; slips of interest 1e-10 to 1e-5 m): the final slip is zero by physics"),
]
INLINE_MAX = 256  # numbers of a file stored inline in outputs.json; more go to values/
MANTISSA_DROP = 17  # 63 - 46: bits of each double's magnitude dropped in values/ blobs
NUMBER = re.compile(r"(?<![A-Za-z_#\d.])[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")

# ---------------------------------------------------------------------------------------
# What is excluded as non-deterministic (by file pattern), and why
# ---------------------------------------------------------------------------------------
# JSON keys dropped before fingerprinting: (file glob, dotted key)
NONDETERMINISTIC_JSON_KEYS = [
    ("identify/*/identification.json", "wall_seconds"),  # wall-clock time of the fit
    ("design/design.json", "wall_seconds"),  # wall-clock time of identify --design
]
# The top-level JSON object dropped from every JSON output before fingerprinting
# (docs/outputs.md: contactwave version, git commit, input hashes, command line, date)
PROVENANCE = "provenance"
# Regex substitutions applied to the text before hashing (HTML) or comparing (stdout):
# (file glob, regex, replacement). The temporary output folder is replaced by <OUT> in
# every stdout before these apply.
NONDETERMINISTIC_TEXT = [
    # report.html: "Generated by ... version 0.1.0 in 19.0 s (1489 simulations)"
    ("reproduce/report.html", r"version [0-9A-Za-z.+-]+ in [0-9.]+ s", "version <V> in <T> s"),
    # report.html, per chapter: "13 figures, 953 simulations, 4.0 s."
    ("reproduce/report.html", r"( simulations), [0-9.]+ s\.", r"\1, <T> s."),
    # report.html, finite_crack figures: "cost (--quick resolution): 16 runs, 38.80 s wall time"
    ("reproduce/report.html", r"(runs), [0-9.e+-]+ s wall time", r"\1, <T> s wall time"),
    # identification.html: "28840 forward runs in 58.89 s."
    ("identify/*/identification.html", r"(forward runs) in [0-9.]+ s", r"\1 in <T> s"),
    # stdout of reproduce: "chapter3: 13 figures, 953 simulations, 4.1 s" and
    # "wrote 66 files to <OUT>/reproduce (open <OUT>/reproduce/report.html) in 26.8 s"
    ("stdout/reproduce.txt", r"( simulations), [0-9.]+ s$", r"\1, <T> s"),
    ("stdout/reproduce.txt", r"(report\.html\)) in [0-9.]+ s$", r"\1 in <T> s"),
    # stdout of run, convergence: "wall time  3.1 ms"
    ("stdout/*", r"^(wall time\s+).*$", r"\1<T>"),
    # stdout of identify: "21543 forward runs in 96.71 s (223 runs/s)"
    ("stdout/*", r"(forward runs) in [0-9.]+ s \([0-9.]+ runs/s\)", r"\1 in <T> s"),
    # stdout of identify --design: "(...; 450 forward runs in 0.57 s)"
    ("stdout/*", r"(forward runs) in [0-9.]+ s\)", r"\1 in <T> s)"),
]
# CSV files whose rows come in completion order (parallel runs): sorted by the first column
SORTED_CSV = [
    "sweep/*/sweep.csv",
    "shards/*/sweep.csv",
]


# ---------------------------------------------------------------------------------------
# The commands
# ---------------------------------------------------------------------------------------
def is_sweep_file(path):
    """A sweep file has a top-level `base = ...` key or an `[[axis]]` table."""
    top_level = True
    for line in path.read_text(encoding="utf-8").splitlines():
        s = line.strip()
        if s.startswith("[[axis]]"):
            return True
        if s.startswith("["):
            top_level = False
        elif top_level and re.match(r"base\s*=", s):
            return True
    return False


def is_bar_stack(path):
    """A bar-stack scenario says `kind = "bar_stack"` (in [model]); `law` takes half-spaces."""
    text = path.read_text(encoding="utf-8")
    return re.search(r'^\s*kind\s*=\s*"bar_stack"', text, flags=re.MULTILINE) is not None


def commands():
    """(name, argv after the binary, stdout kind). `{OUT}` stands for the output folder;
    a command's stdout is fingerprinted as stdout/<name>.txt (or .csv)."""
    ex = ROOT / "examples"
    scenarios = [p for p in sorted(ex.glob("*.toml")) if not is_sweep_file(p)]
    sweeps = [p for p in sorted(ex.glob("*.toml")) if is_sweep_file(p)]
    thesis = [p for p in sorted((ex / "thesis").glob("*.toml")) if not is_sweep_file(p)]
    shear = sorted((ex / "shear").glob("*.toml"))
    rel = lambda p: p.relative_to(ROOT).as_posix()  # noqa: E731
    # --quick: the finite_crack chapter at its CI resolution (the others run alike)
    cmds = [("reproduce", ["reproduce", "all", "--quick", "--out", "{OUT}/reproduce"], "txt")]
    # shear waves and friction (examples/shear): runs, laws and sweeps
    for p in shear:
        if is_sweep_file(p):
            cmds.append((f"sweep_shear_{p.stem}",
                         ["sweep", rel(p), "--out", f"{{OUT}}/sweep/shear_{p.stem}",
                          "--threads", "2"], "txt"))
        else:
            cmds.append((f"run_shear_{p.stem}",
                         ["run", rel(p), "--out", f"{{OUT}}/run/shear_{p.stem}"], "txt"))
            cmds.append((f"law_shear_{p.stem}",
                         ["law", rel(p), "--out", f"{{OUT}}/law/shear_{p.stem}"], "txt"))
    # oblique incidence (examples/oblique): runs and the pressure x angle sweep
    for p in sorted((ex / "oblique").glob("*.toml")):
        if is_sweep_file(p):
            cmds.append((f"sweep_oblique_{p.stem}",
                         ["sweep", rel(p), "--out", f"{{OUT}}/sweep/oblique_{p.stem}",
                          "--threads", "2"], "txt"))
        else:
            cmds.append((f"run_oblique_{p.stem}",
                         ["run", rel(p), "--out", f"{{OUT}}/run/oblique_{p.stem}"], "txt"))
    for p in scenarios:
        cmds.append((f"run_{p.stem}", ["run", rel(p), "--out", f"{{OUT}}/run/{p.stem}"], "txt"))
    # finite cracks in 2D (examples/solid_2d, every example at its own resolution: the
    # reference case plate_crack.toml is about 20 s on 2 cores) and the quick crack-length
    # sweep of examples/sweeps (crack_length.toml itself is the minutes-long study)
    for p in sorted((ex / "solid_2d").glob("*.toml")):
        cmds.append((f"run_solid_2d_{p.stem}",
                     ["run", rel(p), "--out", f"{{OUT}}/run/solid_2d_{p.stem}"], "txt"))
    for p in sorted((ex / "sweeps").glob("*_quick.toml")):
        cmds.append((f"sweep_{p.stem}",
                     ["sweep", rel(p), "--out", f"{{OUT}}/sweep/{p.stem}", "--threads", "2"],
                     "txt"))
    for p in sweeps:
        cmds.append((f"sweep_{p.stem}",
                     ["sweep", rel(p), "--out", f"{{OUT}}/sweep/{p.stem}", "--threads", "2"],
                     "txt"))
    grid = "examples/stiffness_xi_grid.toml"
    for k in (1, 2):
        cmds.append((f"shard_{k}_of_2",
                     ["sweep", grid, "--out", f"{{OUT}}/shards/{k}", "--shard", f"{k}/2",
                      "--threads", "2"], "txt"))
    cmds.append(("merge", ["merge", "{OUT}/merge/merged.csv", "{OUT}/shards/1/sweep.csv",
                           "{OUT}/shards/2/sweep.csv"], "txt"))
    for p in [p for p in scenarios + thesis if not is_bar_stack(p)]:
        sub = "thesis_" if p.parent.name == "thesis" else ""
        cmds.append((f"law_{sub}{p.stem}",
                     ["law", rel(p), "--out", f"{{OUT}}/law/{sub}{p.stem}"], "txt"))
    cmds.append(("convergence", ["convergence", "examples/rccm_1.6MPa.toml",
                                 "--out", "{OUT}/convergence"], "txt"))
    for p in sorted((ex / "identify").glob("*.toml")):
        if p.stem in IDENTIFY_SKIPPED:
            continue
        cmds.append((f"identify_{p.stem}",
                     ["identify", rel(p), "--out", f"{{OUT}}/identify/{p.stem}"], "txt"))
    und = "examples/identify/rccm_undamaged.toml"
    cmds.append(("identify_design", ["identify", und, "--design", "--out", "{OUT}/design"],
                 "txt"))
    cmds.append(("identify_synthesize",
                 ["identify", und, "--synthesize", "interface.traction.stiffness=2e13",
                  "--noise", "0.01", "--seed", "7"], "csv"))
    table2 = "examples/thesis/table2_contact_stiffness.csv"
    for col in ("stiffness_al_al_pa_per_m", "stiffness_al_pmma_pa_per_m"):
        short = "_".join(col.split("_")[1:3])
        args = ["fit", "power-law", table2, "--columns", f"pressure_pa,{col}"]
        cmds.append((f"fit_{short}", args, "txt"))
        cmds.append((f"fit_{short}_json", args + ["--json"], "json"))
    cmds.append(("fit_default_columns", ["fit", "power-law", table2], "txt"))
    cmds.append(("validate", ["validate"], "txt"))
    return cmds


# tribobrake_power_law: about 2 400 bar-stack forward runs (its recovery is asserted by
# crates/contactwave/tests/all/identify.rs, slow tier, on fewer starts)
IDENTIFY_SKIPPED = {"tribobrake_power_law"}



# ---------------------------------------------------------------------------------------
# Findings: physics asserted on the outputs themselves (record refuses to store outputs
# that break one, so a re-recording cannot accept a lost result)
# ---------------------------------------------------------------------------------------
def recovered(path, truth, width):
    """An identification.json's check: each parameter identified, its estimate within 5 %
    of the truth, its 95 % interval holding the estimate and the truth and narrower than
    `width` times the truth."""
    def check(out):
        d = json.loads((out / path).read_text(encoding="utf-8"))
        problems = []
        for key, true in truth.items():
            est = d["estimates"][key]
            lo, hi = d["intervals"][key]
            if not d["identified"][key]:
                problems.append(f"{key} not identified: {d['verdicts'][key]}")
            if abs(est / true - 1.0) >= 0.05:
                problems.append(f"{key} = {est:.6g}, true {true:.6g} (more than 5 % off)")
            if lo is None or hi is None or not (lo < est < hi and lo < true < hi):
                problems.append(f"{key}: 95 % CI [{lo}, {hi}] misses the estimate {est:.6g} "
                                f"or the truth {true:.6g}")
            elif hi - lo >= width * true:
                problems.append(f"{key}: 95 % CI [{lo:.6g}, {hi:.6g}] wider than "
                                f"{width} x {true:.6g}")
        return problems
    return check


FINDINGS = [
    # examples/identify/crack_closure_friction.toml: the 2D model as the forward model, data
    # synthesised at p0 = 1.5 MPa, mu = 0.4 with 2 % noise (its header and docs/identify.md
    # section 7; the data are what its --synthesize command makes: tests/all/identify_2d.rs)
    ("identify/crack_closure_friction/identification.json: p0 and mu recovered",
     recovered("identify/crack_closure_friction/identification.json",
               {"crack.0.static_pressure": 1.5e6, "crack.0.tangential.friction": 0.4}, 0.15)),
]


def check_findings(out):
    """Prints each finding that fails; returns the number failed."""
    failed = 0
    for what, check in FINDINGS:
        try:
            problems = check(out)
        except (OSError, KeyError, ValueError, TypeError) as e:
            problems = [f"cannot be read: {e!r}"]
        for pr in problems:
            print(f"finding failed: {what}: {pr}")
        failed += bool(problems)
    print(f"findings: {len(FINDINGS) - failed} passed, {failed} failed")
    return failed


# ---------------------------------------------------------------------------------------
# Reading an output: its values
# ---------------------------------------------------------------------------------------
def matches(rel, pattern):
    return fnmatch.fnmatchcase(rel, pattern)


def mask_text(rel, text):
    for pattern, regex, repl in NONDETERMINISTIC_TEXT:
        if matches(rel, pattern):
            text = re.sub(regex, repl, text, flags=re.MULTILINE)
    return text


def parse_number(cell):
    """float of a CSV cell, or None if it is not a number."""
    try:
        return float(cell)
    except ValueError:
        return None


def read_column(name, cells):
    """A numeric column: its values (None for an empty cell); a text column: its sha256."""
    try:
        values = list(map(float, cells))  # fast path: every cell a number
    except ValueError:
        values = []
        for c in cells:
            v = parse_number(c)
            if v is None and c.strip() != "":  # a text column: its cells, exactly
                digest = hashlib.sha256("\n".join(cells).encode("utf-8")).hexdigest()
                return {"name": name, "text": True, "n": len(cells), "sha256": digest}
            values.append(v)
    return {"name": name, "n": len(cells), "values": values}


def read_csv(rel, text):
    lines = [ln for ln in text.splitlines() if not ln.startswith("#")]
    if '"' in text:
        rows = list(csv.reader(lines))
    else:
        rows = [ln.split(",") for ln in lines]
    if not rows:
        return {"kind": "csv", "header": [], "rows": 0, "columns": []}
    header, body = rows[0], rows[1:]
    sort = any(matches(rel, p) for p in SORTED_CSV)
    if sort:
        body.sort(key=lambda r: (parse_number(r[0]) if r and parse_number(r[0]) is not None
                                 else math.inf, r))
    width = max([len(header)] + [len(r) for r in body])
    if all(len(r) == width for r in body):
        cols = list(zip(*body)) if body else [()] * width
    else:
        cols = [[r[j] if j < len(r) else "" for r in body] for j in range(width)]
    columns = [read_column(header[j] if j < len(header) else f"#{j}", list(cols[j]))
               for j in range(width)]
    out = {"kind": "csv", "header": header, "rows": len(body), "columns": columns}
    if sort:
        out["sorted_by_first_column"] = True
    return out


def flatten_json(value, prefix, out):
    if isinstance(value, dict):
        for k, v in value.items():
            flatten_json(v, f"{prefix}.{k}" if prefix else str(k), out)
    elif isinstance(value, list):
        if not value:
            out[prefix] = []
        for i, v in enumerate(value):
            flatten_json(v, f"{prefix}.{i}" if prefix else str(i), out)
    else:
        out[prefix] = value


def read_json(rel, text):
    def constant(name):  # NaN / Infinity, as Python's json writes them
        return {"NaN": "NaN", "Infinity": "inf", "-Infinity": "-inf"}[name]

    leaves = {}
    flatten_json(json.loads(text, parse_constant=constant), "", leaves)
    # the checkout's own path (an output folder's manifest names its run by its input,
    # canonicalized): the same in every clone
    root = str(ROOT)
    for k, v in leaves.items():
        if isinstance(v, str) and root in v:
            leaves[k] = v.replace(root, "<ROOT>")
    for pattern, key in NONDETERMINISTIC_JSON_KEYS:
        if matches(rel, pattern):
            leaves.pop(key, None)
    # the "provenance" object of every JSON output (summary.json, findings.json,
    # identification.json, design.json, a sweep's provenance.json): the date and time,
    # the command line with its temporary folder, the commit and the version vary
    for key in [k for k in leaves if k == PROVENANCE or k.startswith(PROVENANCE + ".")]:
        del leaves[key]
    return {"kind": "json", "leaves": leaves}


def read_text_numbers(rel, text):
    """SVG, HTML: the text without its numbers (sha256) and the numbers as printed."""
    numbers = NUMBER.findall(text)
    skeleton = NUMBER.sub("#", text)
    return {"kind": "text", "sha256": hashlib.sha256(skeleton.encode("utf-8")).hexdigest(),
            "n": len(numbers), "numbers": numbers}


def read_output(rel, data):
    suffix = rel.rsplit(".", 1)[-1].lower() if "." in rel else ""
    if suffix == "csv":
        return read_csv(rel, data.decode("utf-8"))
    if suffix == "json":
        return read_json(rel, data.decode("utf-8"))
    if suffix in ("svg", "html"):
        return read_text_numbers(rel, mask_text(rel, data.decode("utf-8")))
    return {"kind": "sha256", "sha256": hashlib.sha256(data).hexdigest()}


# ---------------------------------------------------------------------------------------
# Running
# ---------------------------------------------------------------------------------------
#: Commands that read what others wrote: each runs once those are done.
AFTER = {"merge": {"shard_1_of_2", "shard_2_of_2"}}

#: The longest commands (about 90 to 140 s on 2 cores), started first so that the short
#: ones fill the other worker.
LONG_FIRST = ("reproduce", "validate", "identify_crack_closure_friction")


def run_all(binary, out, ran=None):
    """Runs every command into `out`, JOBS at a time (environment CONTACTWAVE_REF_JOBS,
    default 2: most commands are short and serial, the long ones parallel; outputs do not
    depend on the thread count); returns {relative path: values}. `ran`, a list: each
    command's argv (output folder substituted), exit code and seconds are appended, in the
    order of commands()."""
    from concurrent.futures import ThreadPoolExecutor

    files = {}
    out_str = str(out)
    cmds = commands()
    jobs = max(1, int(os.environ.get("CONTACTWAVE_REF_JOBS", "2")))

    def run_one(name, argv):
        args = [binary] + [a.replace("{OUT}", out_str) for a in argv]
        t0 = time.monotonic()
        proc = subprocess.run(args, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
        return args, proc, time.monotonic() - t0

    first = [c for c in cmds if c[0] in LONG_FIRST and c[0] not in AFTER]
    rest = [c for c in cmds if c[0] not in LONG_FIRST and c[0] not in AFTER]
    done = {}
    with ThreadPoolExecutor(max_workers=jobs) as pool:
        futures = {c[0]: pool.submit(run_one, c[0], c[1]) for c in first + rest}
        for name, argv, _ in cmds:
            if name in AFTER:
                for dep in AFTER[name]:
                    futures[dep].result()
                futures[name] = pool.submit(run_one, name, argv)
        for name, f in futures.items():
            done[name] = f.result()
    timings = []
    for name, argv, kind in cmds:
        args, proc, seconds = done[name]
        timings.append((seconds, name))
        if ran is not None:
            ran.append({"name": name, "argv": args[1:], "exit": proc.returncode,
                        "seconds": round(seconds, 3)})
        stdout = proc.stdout.decode("utf-8", errors="replace").replace(out_str, "<OUT>")
        if proc.returncode != 0:
            err = proc.stderr.decode("utf-8", errors="replace").strip().splitlines()[-5:]
            print(f"note: `{name}` exited with {proc.returncode}: " + " | ".join(err),
                  file=sys.stderr)
        rel = f"stdout/{name}.{kind}"
        if kind == "txt":
            fp = {"kind": "stdout", "exit": proc.returncode,
                  "lines": mask_text(rel, stdout).splitlines()}
        else:
            fp = read_output(rel, stdout.encode("utf-8"))
            fp["exit"] = proc.returncode
        files[rel] = fp
    for path in sorted(out.rglob("*")):
        if path.is_file():
            rel = path.relative_to(out).as_posix()
            files[rel] = read_output(rel, path.read_bytes())
    slow = ", ".join(f"{n} {t:.1f} s" for t, n in sorted(timings, reverse=True)[:4])
    print(f"ran {len(timings)} commands in {sum(t for t, _ in timings):.1f} s "
          f"(slowest: {slow})")
    return files


# ---------------------------------------------------------------------------------------
# Storing: outputs.json (readable) and values/<file>.xz (the numbers of big files)
# ---------------------------------------------------------------------------------------
def encode_values(values):
    """Numbers (None: empty cell) -> 7 byte planes of the zigzagged second differences of
    the upper 46 bits of each double (sign and magnitude). NaN stands for an empty cell."""
    doubles = array.array("d", [math.nan if v is None else v for v in values])
    words = array.array("Q")
    words.frombytes(doubles.tobytes())
    sign = 1 << 63
    half = 1 << (MANTISSA_DROP - 1)
    ints = [-(((w ^ sign) + half) >> MANTISSA_DROP) if w & sign
            else (w + half) >> MANTISSA_DROP for w in words]
    for _ in range(2):
        ints = ints[:1] + [b - a for a, b in zip(ints, ints[1:])]
    zz = [x << 1 if x >= 0 else ((-x) << 1) - 1 for x in ints]
    return b"".join(bytes((x >> (8 * j)) & 255 for x in zz) for j in range(7))


def decode_values(data, n):
    planes = [data[j * n:(j + 1) * n] for j in range(7)]
    zz = [a | b << 8 | c << 16 | d << 24 | e << 32 | f << 40 | g << 48
          for a, b, c, d, e, f, g in zip(*planes)]
    ints = [x >> 1 if not x & 1 else -((x + 1) >> 1) for x in zz]
    for _ in range(2):
        acc, out = 0, []
        for x in ints:
            acc += x
            out.append(acc)
        ints = out
    words = array.array("Q", [(((-m) << MANTISSA_DROP) | (1 << 63)) if m < 0
                              else m << MANTISSA_DROP for m in ints])
    doubles = array.array("d")
    doubles.frombytes(words.tobytes())
    return list(doubles)


def count_numbers(fp):
    if fp["kind"] == "csv":
        return sum(c["n"] for c in fp["columns"] if not c.get("text"))
    return fp["n"] if fp["kind"] == "text" else 0


def blob_path(values_dir, rel):
    return values_dir / (rel + ".xz")


def stored_form(rel, fp, values_dir):
    """The entry of outputs.json, and the bytes of values/<rel>.xz (None: inline)."""
    entry = {k: v for k, v in fp.items() if k not in ("columns", "numbers")}
    big = count_numbers(fp) > INLINE_MAX
    blob = None
    if fp["kind"] == "csv":
        cols, parts = [], []
        for c in fp["columns"]:
            if c.get("text"):
                cols.append(c)
                continue
            col = {"name": c["name"], "n": c["n"]}
            finite = [v for v in c["values"] if v is not None and math.isfinite(v)]
            if finite:
                col["min"], col["max"] = min(finite), max(finite)
            empty = [i for i, v in enumerate(c["values"]) if v is None]
            if empty:
                col["empty"] = empty
            if big:
                parts.append(encode_values(c["values"]))
            else:
                col["values"] = [json_number(v) for v in c["values"]]
            cols.append(col)
        entry["columns"] = cols
        if big:
            blob = b"".join(parts)
    elif fp["kind"] == "text":
        if big:
            blob = "\n".join(fp["numbers"]).encode("ascii")
        else:
            entry["numbers"] = fp["numbers"]
    if blob is not None:
        entry["values"] = blob_path(Path("values"), rel).as_posix()
    return entry, blob


def json_number(v):
    """NaN and infinities as strings (outputs.json is strict JSON)."""
    if v is None or math.isfinite(v):
        return v
    return "NaN" if math.isnan(v) else ("inf" if v > 0 else "-inf")


def from_json_number(v):
    return float(v) if isinstance(v, str) else v


def load_reference(ref_path):
    """{rel: values} of the stored references, the blobs of values/ decoded."""
    reference = json.loads(ref_path.read_text(encoding="utf-8"))
    if reference.get("format") != FORMAT:
        sys.exit(f"{ref_path}: format {reference.get('format')}, expected {FORMAT}: "
                 "re-record (after `check` of the old format passed on the same code)")
    files = {}
    for rel, entry in reference["files"].items():
        fp = dict(entry)
        blob = None
        if "values" in entry:
            path = ref_path.parent / entry["values"]
            try:
                blob = lzma.decompress(path.read_bytes())
            except (OSError, lzma.LZMAError) as e:
                sys.exit(f"{path}: cannot be read ({e}): re-record")
            fp.pop("values")
        if fp["kind"] == "csv":
            offset, cols = 0, []
            for c in entry["columns"]:
                c = dict(c)
                if not c.get("text"):
                    if blob is not None:
                        n = c["n"]
                        c["values"] = decode_values(blob[offset:offset + 7 * n], n)
                        offset += 7 * n
                    else:
                        c["values"] = [from_json_number(v) for v in c["values"]]
                    for i in c.get("empty", []):
                        c["values"][i] = None
                cols.append(c)
            fp["columns"] = cols
        elif fp["kind"] == "text" and blob is not None:
            fp["numbers"] = blob.decode("ascii").split("\n") if fp["n"] else []
        files[rel] = fp
    return files


def dump_reference(files, path):
    """outputs.json, one line per CSV column / JSON leaf / stdout line (readable diffs), and
    values/<file>.xz for the numbers of the big files; stale blobs removed, and a blob whose
    numbers did not change left as it is (no churn from another xz version)."""
    values_dir = path.parent / "values"
    out = ["{", f' "format": {FORMAT},', f' "rel_tol": {REL_TOL!r},',
           f' "column_floor": {COLUMN_FLOOR!r},', f' "text_floor": {TEXT_FLOOR!r},',
           ' "files": {']
    items = sorted(files.items())
    written = set()
    for n, (rel, fp) in enumerate(items):
        entry, blob = stored_form(rel, fp, values_dir)
        if blob is not None:
            target = blob_path(values_dir, rel)
            written.add(target)
            old = None
            if target.exists():
                try:
                    old = lzma.decompress(target.read_bytes())
                except lzma.LZMAError:
                    old = None
            if old != blob:
                target.parent.mkdir(parents=True, exist_ok=True)
                target.write_bytes(lzma.compress(blob, preset=9 | lzma.PRESET_EXTREME))
        body = []
        for key, value in entry.items():
            if key == "columns":
                cols = ",\n".join("    " + json.dumps(c, allow_nan=False) for c in value)
                body.append(f'   "columns": [\n{cols}\n   ]')
            elif key == "leaves" and value:
                inner = ",\n".join(
                    f"    {json.dumps(k)}: {json.dumps(json_number_leaf(v), allow_nan=False)}"
                    for k, v in value.items())
                body.append(f'   "leaves": {{\n{inner}\n   }}')
            elif key == "lines" and value:
                inner = ",\n".join("    " + json.dumps(v) for v in value)
                body.append(f'   "lines": [\n{inner}\n   ]')
            else:
                body.append(f"   {json.dumps(key)}: {json.dumps(value, allow_nan=False)}")
        comma = "," if n + 1 < len(items) else ""
        out.append(f"  {json.dumps(rel)}: {{\n" + ",\n".join(body) + f"\n  }}{comma}")
    out += [" }", "}", ""]
    text = "\n".join(out)
    json.loads(text)  # well-formed
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text, encoding="utf-8")
    if values_dir.exists():
        for stale in sorted(values_dir.rglob("*.xz")):
            if stale not in written:
                stale.unlink()
        for d in sorted(values_dir.rglob("*"), reverse=True):
            if d.is_dir() and not any(d.iterdir()):
                d.rmdir()
    blobs = sum(p.stat().st_size for p in values_dir.rglob("*.xz")) if values_dir.exists() else 0
    return path.stat().st_size, len(written), blobs


def json_number_leaf(v):
    return json_number(v) if isinstance(v, float) else v


# ---------------------------------------------------------------------------------------
# Comparing
# ---------------------------------------------------------------------------------------
def named_floor(name):
    for regex, floor, _why in ROUNDOFF_FLOORS:
        if re.search(regex, name, flags=re.IGNORECASE):
            return floor
    return 0.0


def is_number(v):
    return isinstance(v, (int, float)) and not isinstance(v, bool)


def agree(a, b, floor):
    """Two values (None: empty cell) within REL_TOL relative plus `floor`; NaN equals NaN,
    infinities and empty cells exactly."""
    if a is None or b is None:
        return a is b
    if a == b:
        return True
    if not (math.isfinite(a) and math.isfinite(b)):
        return math.isnan(a) and math.isnan(b)
    return abs(a - b) <= REL_TOL * max(abs(a), abs(b)) + floor


def rel_change(a, b):
    if isinstance(a, str) and isinstance(b, str):  # numbers in text, as printed
        try:
            a, b = float(a), float(b)
        except ValueError:
            return ""
    if not (is_number(a) and is_number(b)):
        return ""
    if a == b:
        return ", relative change 0"
    scale = max(abs(a), abs(b))
    return f", relative change {abs(a - b) / scale:.3e}" if scale else ""


def last_digit_unit(token):
    """One unit in the last printed digit of a number token; None for an integer."""
    mant, _, exp = token.lower().partition("e")
    if not exp and "." not in mant:
        return None
    decimals = len(mant.split(".", 1)[1]) if "." in mant else 0
    return 10.0 ** (int(exp or 0) - decimals)


def text_numbers_agree(a, b, integer_slack):
    """Numbers in text as printed (see TEXT_TOLERANCE in the module doc)."""
    if a == b:
        return True
    x, y = float(a), float(b)
    unit = last_digit_unit(a)
    if unit is None:
        if last_digit_unit(b) is None:
            return abs(x - y) <= integer_slack
        unit = 0.0
    return (abs(x - y) <= REL_TOL * max(abs(x), abs(y)) + 1e-9 * unit + unit
            or max(abs(x), abs(y)) < TEXT_FLOOR)


def compare_values(where, a_vals, b_vals, floor, diffs):
    """Appends (what, old, new) for each value that differs."""
    if len(a_vals) != len(b_vals):
        diffs.append((f"{where}: count", len(a_vals), len(b_vals)))
        return
    for i, (a, b) in enumerate(zip(a_vals, b_vals)):
        if a != b and not agree(a, b, floor):
            diffs.append((f"{where} row {i + 1}", a, b))


def column_floor(name, values):
    scale = max((abs(v) for v in values if v is not None and math.isfinite(v)), default=0.0)
    return max(COLUMN_FLOOR * scale, named_floor(name))


def json_floors(leaves):
    """Floor of each numeric leaf: its name's, and COLUMN_FLOOR times the largest |value|
    of its list (keys with list indices, grouped with the indices replaced by *)."""
    group = {}
    for key, v in leaves.items():
        if is_number(v):
            g = re.sub(r"(^|\.)\d+(?=\.|$)", r"\1*", key)
            if g != key and math.isfinite(v):
                group[g] = max(group.get(g, 0.0), abs(v))
    floors = {}
    for key, v in leaves.items():
        if is_number(v):
            g = re.sub(r"(^|\.)\d+(?=\.|$)", r"\1*", key)
            floors[key] = max(named_floor(key), COLUMN_FLOOR * group.get(g, 0.0))
    return floors


def compare_lines(ref_lines, now_lines, integer_slack, diffs):
    for i in range(max(len(ref_lines), len(now_lines))):
        la = ref_lines[i] if i < len(ref_lines) else "<none>"
        lb = now_lines[i] if i < len(now_lines) else "<none>"
        if la == lb:
            continue
        na, nb = NUMBER.findall(la), NUMBER.findall(lb)
        if (NUMBER.sub("#", la) != NUMBER.sub("#", lb) or len(na) != len(nb)
                or not all(text_numbers_agree(x, y, integer_slack) for x, y in zip(na, nb))):
            diffs.append((f"line {i + 1}", la, lb))


def compare(ref, now):
    """List of (what, reference, now) differences of one file."""
    if ref.get("kind") != now.get("kind"):
        return [("kind", ref.get("kind"), now.get("kind"))]
    kind = ref["kind"]
    diffs = []
    if ref.get("exit") != now.get("exit"):
        diffs.append(("exit code", ref.get("exit"), now.get("exit")))
    if kind == "stdout":
        compare_lines(ref["lines"], now["lines"], 0, diffs)
    elif kind == "sha256":
        if ref["sha256"] != now["sha256"]:
            diffs.append(("sha256", ref["sha256"][:16], now["sha256"][:16]))
    elif kind == "text":
        if ref["sha256"] != now["sha256"]:
            diffs.append(("text without its numbers (sha256)", ref["sha256"][:16],
                          now["sha256"][:16]))
        elif ref["n"] != now["n"]:
            diffs.append(("count of numbers", ref["n"], now["n"]))
        else:
            for i, (a, b) in enumerate(zip(ref["numbers"], now["numbers"])):
                if a != b and not text_numbers_agree(a, b, 1):
                    diffs.append((f"number {i + 1}", a, b))
    elif kind == "json":
        a, b = ref["leaves"], now["leaves"]
        floors = json_floors(a)
        for key in sorted(set(a) | set(b)):
            if key not in a or key not in b:
                diffs.append((key, a.get(key, "<missing>"), b.get(key, "<missing>")))
                continue
            x, y = a[key], b[key]
            if is_number(x) and is_number(y):
                if not agree(float(x), float(y), floors.get(key, 0.0)):
                    diffs.append((key, x, y))
            elif x != y:
                diffs.append((key, x, y))
    elif kind == "csv":
        if ref["header"] != now["header"]:
            diffs.append(("header", ",".join(ref["header"]), ",".join(now["header"])))
        if ref["rows"] != now["rows"]:
            diffs.append(("rows", ref["rows"], now["rows"]))
        rc, nc = ref["columns"], now["columns"]
        if len(rc) != len(nc):
            diffs.append(("columns", len(rc), len(nc)))
        for col_r, col_n in zip(rc, nc):
            name = col_r["name"]
            if col_r.get("text") or col_n.get("text"):
                if col_r.get("sha256") != col_n.get("sha256"):
                    diffs.append((f"{name}: text cells (sha256)", col_r.get("sha256", "")[:16],
                                  col_n.get("sha256", "")[:16]))
                continue
            compare_values(name, col_r["values"], col_n["values"],
                           column_floor(name, col_r["values"]), diffs)
    return diffs


def fmt(v):
    return repr(v) if isinstance(v, float) else str(v)


def report(ref_files, now_files, limit, verb):
    """Prints the differences (at most `limit` per file; None: all); returns (passed,
    failed, changed values)."""
    passed = failed = changed = 0
    for rel in sorted(set(ref_files) | set(now_files)):
        if rel not in now_files:
            print(f"{rel}: missing ({verb}, not written now)")
            failed += 1
            continue
        if rel not in ref_files:
            print(f"{rel}: extra (written now, not {verb})")
            failed += 1
            continue
        diffs = compare(ref_files[rel], now_files[rel])
        if diffs:
            failed += 1
            changed += len(diffs)
            for what, a, b in diffs[:limit]:
                print(f"{rel}: {what}: reference {fmt(a)}, now {fmt(b)}{rel_change(a, b)}")
            if limit is not None and len(diffs) > limit:
                print(f"{rel}: ... {len(diffs) - limit} more differences (--all lists them)")
        else:
            passed += 1
    return passed, failed, changed


def git_state():
    """(commit, clean): HEAD's commit and whether the work tree (tracked and untracked,
    not ignored files) equals it; (None, False) outside a git checkout."""
    try:
        commit = subprocess.run(["git", "rev-parse", "HEAD"], cwd=ROOT, check=True,
                                capture_output=True, text=True).stdout.strip()
        # --no-optional-locks: a status that rewrote the index would make the library's
        # build script (which watches the index) run again, and the wheel's build then
        # compile the library again
        status = subprocess.run(["git", "--no-optional-locks", "status", "--porcelain"],
                                cwd=ROOT, check=True,
                                capture_output=True, text=True).stdout
    except (OSError, subprocess.CalledProcessError):
        return None, False
    return commit, status.strip() == ""


def sha256_file(path):
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def write_ran(path, binary, out, ran):
    """The list of commands run into `out` (see --ran), with what makes it reusable: the
    commit of a clean work tree and the binary's sha256."""
    commit, clean = git_state()
    doc = {"commit": commit, "clean": clean, "binary_sha256": sha256_file(binary),
           "out": str(out), "commands": ran}
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(doc, indent=1) + "\n", encoding="utf-8")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("mode", choices=["record", "check"])
    ap.add_argument("--bin", default=str(ROOT / "target" / "release" / "contactwave"),
                    help="the contactwave binary (default: target/release/contactwave)")
    ap.add_argument("--ref", default=str(ROOT / "tests" / "reference" / "outputs.json"),
                    help="the reference file (default: tests/reference/outputs.json; its "
                         "big files' values in values/ beside it)")
    ap.add_argument("--keep", metavar="DIR",
                    help="write the outputs into DIR (emptied first) and keep them")
    ap.add_argument("--all", action="store_true",
                    help="check: list every differing value, not the first 20 per file")
    ap.add_argument("--ran", metavar="FILE",
                    help="with --keep: write the commands run (argv, exit code, seconds), "
                         "the commit and the binary's sha256 to FILE (JSON), so that "
                         "scripts/doc_commands.py --ran FILE and the browser test reuse "
                         "the outputs in DIR instead of running the same commands again")
    args = ap.parse_args()

    binary = str(Path(args.bin).resolve())
    if not os.access(binary, os.X_OK):
        sys.exit(f"no executable {binary}: "
                 "build it with `cargo build --release -p contactwave-cli`")
    ref_path = Path(args.ref)
    if not ref_path.is_absolute():
        ref_path = (Path.cwd() / ref_path).resolve()
    if args.mode == "check" and not ref_path.exists():
        sys.exit(f"no reference file {ref_path}: run `{sys.argv[0]} record` first")
    if args.ran and not args.keep:
        sys.exit("--ran needs --keep DIR (the outputs that a reuse copies)")
    t0 = time.monotonic()
    if args.keep:
        out = Path(args.keep).resolve()
        if out.exists():
            shutil.rmtree(out)
        out.mkdir(parents=True)
        ran = []
        if args.ran:
            Path(args.ran).unlink(missing_ok=True)  # a stale list never describes DIR
        files = run_all(binary, out, ran)
        findings_failed = check_findings(out)
        if args.ran and not findings_failed:
            write_ran(Path(args.ran), binary, out, ran)
    else:
        with tempfile.TemporaryDirectory(prefix="contactwave-ref-") as tmp:
            files = run_all(binary, Path(tmp))
            findings_failed = check_findings(Path(tmp))
    if args.mode == "record" and findings_failed:
        print("error: not recorded: outputs that break a finding (FINDINGS) are no reference",
              file=sys.stderr)
        return 1
    if args.mode == "record":
        old_format = None
        if ref_path.exists():
            old_format = json.loads(ref_path.read_text(encoding="utf-8")).get("format")
        if old_format == FORMAT:
            print("values that change against the stored references:")
            _, failed, changed = report(load_reference(ref_path), files, None, "recorded")
            print(f"{changed} differences in {failed} files")
        elif old_format is not None:
            print(f"the stored references have format {old_format}: no value-by-value "
                  "comparison (run `check` of that format on the same code first)")
        size, blobs, blob_bytes = dump_reference(files, ref_path)
        print(f"recorded {len(files)} files into {ref_path} ({size / 1024:.0f} KiB) and "
              f"{blobs} value files ({blob_bytes / 1024:.0f} KiB) in "
              f"{time.monotonic() - t0:.0f} s")
        return 0
    passed, failed, _ = report(load_reference(ref_path), files,
                               None if args.all else 20, "in the reference")
    print(f"{passed} passed, {failed} failed")
    print(f"reference check took {time.monotonic() - t0:.0f} s", file=sys.stderr)
    return 0 if failed == 0 and findings_failed == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
