#!/usr/bin/env python3
"""Time to refusal of the hostile CLI cases (issue 12; the same cases as
crates/contactwave-cli/tests/all/hostile.rs): runs each against the release CLI with
CONTACTWAVE_MEMORY_BUDGET=2G and prints a markdown table (case, exit code, first line of
stderr, wall time) for docs/hardening.md.

    cargo build --release
    python3 scripts/hostile_timings.py [--bin target/release/contactwave]

Signals: the command is started, SIGINT or SIGTERM is sent after a delay, and the time
is measured from the signal to the exit. Each case's output folder must not exist
afterwards (except where the case writes its files and then exits 1 or 0)."""

import argparse
import math
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
EXAMPLES = ROOT / "examples"

HALF_SPACE = """[medium]
material = "pmma"
[interface]
static_pressure = 0.082e6
[incident]
frequency = 1e6
cycles = 15
amplitude = 0.82e6
"""


def with_line(text, key, value):
    out, done = [], False
    for line in text.splitlines():
        if not done and line.lstrip().startswith(f"{key} ="):
            out.append(f"{key} = {value}")
            done = True
        else:
            out.append(line)
    return "\n".join(out) + "\n"


def tribobrake():
    return (EXAMPLES / "tribobrake.toml").read_text()


def sweep(axis):
    return f'base = "{EXAMPLES / "unilateral.toml"}"\n{axis}'


FAILING_BASE = """[medium]
material = "pmma"
[interface]
static_pressure = 0.1e6
compression = { law = "power", c = 1e11, m = 0.5 }
[incident]
frequency = 1e6
cycles = 5
xi = 0.5
[solver]
samples_per_period = 32
"""

FAILING_ID = """base = "base.toml"
observed = ["A2_over_A1"]
[data]
"incident.xi" = [0.3, 0.5, 0.8]
A2_over_A1 = [0.01, 0.02, 0.03]
[[parameter]]
key = "interface.compression.c"
bounds = [1e10, 1e300]
scale = "log"
initial = 1e11
[fit]
particles = 4
iterations = 2
local_iterations = 10
local_starts = 1
bootstrap = 0
"""


def bar_stack_incident_file(duration_line):
    return f"""[model]
kind = "bar_stack"
area = 1.0
static_force = 0.082e6
first_end = "transparent"
last_end = "transparent"
{duration_line}
[[segment]]
name = "upper"
length = 0.005
material = "pmma"
[[segment]]
name = "lower"
length = 0.005
material = "pmma"
[[interface]]
between = ["upper", "lower"]
compression = {{ law = "rigid" }}
traction = {{ law = "rccm", stiffness = 2e13, energy = 0.1 }}
[incident]
kind = "file"
path = "wave.csv"
frequency = 1e6
amplitude = 2.5e6
"""


def write_wave(path, rows):
    """A 1 MHz sine sampled every ns, ramped up over 3 periods."""
    with open(path, "w") as f:
        f.write("t,s\n")
        for k in range(rows):
            s = math.sin(2 * math.pi * k / 1000) * min(1.0, k / 3000)
            f.write(f"{k}e-9,{s:.3f}\n")


RUN = ["run", "case.toml", "--out", "out"]
SWEEP = ["sweep", "case.toml", "--out", "out"]
ONE_POINT = sweep('[[axis]]\nparameter = "incident.xi"\nvalues = [0.3]\n')

# (name, files {name: text}, args, env, signal or None, delay before the signal in s)
CASES = [
    ("burst of 1e9 cycles", {"case.toml": with_line(HALF_SPACE, "cycles", "1e9")}, RUN),
    ("frequency 1e15 Hz", {"case.toml": with_line(HALF_SPACE, "frequency", "1e15")}, RUN),
    ("probe 10 km away", {"case.toml": HALF_SPACE + "[probe]\nx = -1e4\n"}, RUN),
    (
        "tail of 1e5 periods at 1e5 samples per period",
        {"case.toml": HALF_SPACE + "[solver]\ntail_periods = 1e5\nsamples_per_period = 100000\n"},
        RUN,
    ),
    ("bar stack of 1000 s", {"case.toml": with_line(tribobrake(), "duration", "1e3")}, RUN),
    ("bar stack of 20 s", {"case.toml": with_line(tribobrake(), "duration", "20.0")}, RUN),
    (
        "bar stack segment of 1000 km",
        {"case.toml": tribobrake().replace("length = 0.229", "length = 1e6", 1)},
        RUN,
    ),
    (
        "overflowing Young's modulus",
        {
            "case.toml": with_line(
                HALF_SPACE, "material", '"pmma"\nyoungs_modulus = 1e308\ndensity = 1e-308'
            )
        },
        RUN,
    ),
    ("NaN frequency", {"case.toml": with_line(HALF_SPACE, "frequency", "nan")}, RUN),
    ("infinite amplitude", {"case.toml": with_line(HALF_SPACE, "amplitude", "inf")}, RUN),
    ("negative cycles", {"case.toml": with_line(HALF_SPACE, "cycles", "-3")}, RUN),
    ("empty file", {"case.toml": ""}, RUN),
    ("binary garbage", {"case.toml": "\x00\x01\x02[[[\xff"}, RUN),
    (
        "sweep of 1e7 points",
        {
            "case.toml": sweep(
                '[[axis]]\nparameter = "incident.xi"\nlinspace = [0.1, 1.0, 1000000]\n'
                '[[axis]]\nparameter = "interface.static_pressure"\nlinspace = [1e5, 1e6, 10]\n'
            )
        },
        SWEEP,
    ),
    ("--threads 100000", {"case.toml": ONE_POINT}, SWEEP + ["--threads", "100000"]),
    ("--threads 0", {"case.toml": ONE_POINT}, SWEEP + ["--threads", "0"]),
    ("missing scenario file", {}, ["run", "missing.toml", "--out", "out"]),
    ("scenario is a folder", {}, ["run", ".", "--out", "out"]),
    ("--out names a file", {"case.toml": HALF_SPACE, "afile": "x"}, ["run", "case.toml", "--out", "afile"]),
    (
        "CONTACTWAVE_MEMORY_BUDGET=lots",
        {"case.toml": HALF_SPACE},
        RUN,
        {"CONTACTWAVE_MEMORY_BUDGET": "lots"},
    ),
    (
        "excitation file of 2 MB, budget 1 MB",
        {
            "case.toml": '[medium]\nmaterial = "pmma"\n[interface]\nstatic_pressure = 0.082e6\n'
            '[incident]\nkind = "file"\nfrequency = 1e6\npath = "wave.csv"\n',
            "wave.csv": 80_000,
        },
        RUN,
        {"CONTACTWAVE_MEMORY_BUDGET": "1M"},
    ),
    (
        "bar-stack incident file of 10^7 rows (170 MB), no model.duration, budget 100 MB",
        {"case.toml": bar_stack_incident_file(""), "wave.csv": 10_000_000},
        RUN,
        {"CONTACTWAVE_MEMORY_BUDGET": "100M"},
    ),
    (
        "bar-stack incident file of 10^7 rows, model.duration = 50 us, budget 100 MB (runs)",
        {"case.toml": bar_stack_incident_file("duration = 50e-6"), "wave.csv": 10_000_000},
        RUN,
        {"CONTACTWAVE_MEMORY_BUDGET": "100M"},
    ),
    (
        "identify with failed forward runs (power law C up to 1e300)",
        {"base.toml": FAILING_BASE, "id.toml": FAILING_ID},
        ["identify", "id.toml", "--out", "out"],
    ),
    (
        "sweep with a failed point (power law C = 1e300)",
        {
            "base.toml": FAILING_BASE,
            "case.toml": 'base = "base.toml"\n[[axis]]\nparameter = "interface.compression.c"\n'
            "values = [1e11, 1e300]\n",
        },
        SWEEP,
    ),
    (
        "run of 4 s of Tribobrake + SIGINT after 0.7 s",
        {"case.toml": with_line(tribobrake(), "duration", "4.0")},
        RUN,
        {"CONTACTWAVE_MEMORY_BUDGET": "50G"},
        signal.SIGINT,
        0.7,
    ),
    (
        "run of 4 s of Tribobrake + SIGTERM after 0.7 s",
        {"case.toml": with_line(tribobrake(), "duration", "4.0")},
        RUN,
        {"CONTACTWAVE_MEMORY_BUDGET": "50G"},
        signal.SIGTERM,
        0.7,
    ),
    (
        "identify rccm_undamaged + SIGINT after 1.5 s",
        {},
        ["identify", str(EXAMPLES / "identify" / "rccm_undamaged.toml"), "--out", "out"],
        {},
        signal.SIGINT,
        1.5,
    ),
    (
        "sweep of 6 slow bar-stack points + SIGINT after 0.7 s",
        {
            "long.toml": with_line(tribobrake(), "duration", "4.0"),
            "case.toml": 'base = "long.toml"\n[[axis]]\nparameter = "excitation.peak"\n'
            "values = [5.0, 10.0, 15.0, 20.0, 25.0, 30.0]\n",
        },
        SWEEP + ["--threads", "2"],
        {"CONTACTWAVE_MEMORY_BUDGET": "50G"},
        signal.SIGINT,
        0.7,
    ),
]


def run_case(binary, case):
    name, files, args = case[0], case[1], case[2]
    env_extra = case[3] if len(case) > 3 else {}
    sig = case[4] if len(case) > 4 else None
    delay = case[5] if len(case) > 5 else 0.0
    d = Path(tempfile.mkdtemp(prefix="contactwave-timings-"))
    try:
        for fname, content in files.items():
            if isinstance(content, int):
                write_wave(d / fname, content)
            else:
                (d / fname).write_text(content, errors="surrogateescape")
        env = dict(os.environ)
        env["CONTACTWAVE_MEMORY_BUDGET"] = "2G"
        env.update(env_extra)
        p = subprocess.Popen(
            [binary] + args,
            cwd=d,
            env=env,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.PIPE,
            text=True,
            errors="replace",
        )
        t0 = time.perf_counter()
        if sig is not None:
            time.sleep(delay)
            t0 = time.perf_counter()
            p.send_signal(sig)
        _, err = p.communicate()
        took = time.perf_counter() - t0
        lines = [l for l in err.splitlines() if l.strip()]
        # the error line if any (a sweep may warn before it), else the first line
        first = next(
            (l for l in lines if l.startswith("error:")),
            next((l for l in lines if l.startswith(("interrupted", "warning:"))), lines[0] if lines else ""),
        )
        wrote = (d / "out").exists()
        return name, p.returncode, first, took, wrote, sig is not None
    finally:
        shutil.rmtree(d, ignore_errors=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--bin", default=str(ROOT / "target" / "release" / "contactwave"))
    a = ap.parse_args()
    if not Path(a.bin).exists():
        sys.exit(f"{a.bin}: not found (cargo build --release)")
    print("| case | exit | first line of stderr | time |")
    print("|---|---|---|---|")
    bad = 0
    for case in CASES:
        name, code, first, took, wrote, signalled = run_case(a.bin, case)
        if code not in (0, 1, 2, 130):
            bad += 1
        first = first.replace("|", "\\|").replace(str(ROOT) + "/", "")
        if len(first) > 220:
            first = first[:217] + "..."
        what = "after the signal" if signalled else ""
        out = " (out/ written)" if wrote else ""
        print(f"| {name} | {code}{out} | `{first}` | {took * 1e3:.0f} ms {what} |".replace("  |", " |"))
        sys.stdout.flush()
    if bad:
        sys.exit(f"{bad} case(s) ended with an exit code other than 0, 1, 2, 130")


if __name__ == "__main__":
    main()
