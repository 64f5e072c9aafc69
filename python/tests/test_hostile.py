"""Hostile inputs from Python (issue 12): the cases of the CLI's hostile suite raise
exceptions (ValueError for sizes and numbers, FileNotFoundError for files,
KeyboardInterrupt for Ctrl-C) and leave the interpreter alive: nothing reachable from
Python aborts the process."""

import os
import signal
import threading
import time
import warnings

import numpy as np

import pytest

import contactwave as cw

HALF_SPACE = {
    "medium": {"material": "pmma"},
    "interface": {"static_pressure": 0.082e6},
    "incident": {"frequency": 1e6, "cycles": 15, "amplitude": 0.82e6},
}


def with_(d, section, **kv):
    out = {k: dict(v) for k, v in d.items()}
    out.setdefault(section, {}).update(kv)
    return out


@pytest.fixture(autouse=True)
def fixed_budget(monkeypatch):
    # the refusals do not depend on the machine
    monkeypatch.setenv("CONTACTWAVE_MEMORY_BUDGET", "2G")


SIZE_CASES = [
    ("burst of 1e9 cycles", with_(HALF_SPACE, "incident", cycles=1e9), "incident.cycles"),
    ("frequency 1e15 Hz", with_(HALF_SPACE, "incident", frequency=1e15), "probe.x"),
    ("probe 10 km away", with_(HALF_SPACE, "probe", x=-1e4), "probe.x"),
    (
        "tail of 1e5 periods",
        with_(HALF_SPACE, "solver", tail_periods=1e5, samples_per_period=100000),
        "solver.tail_periods",
    ),
    ("NaN frequency", with_(HALF_SPACE, "incident", frequency=float("nan")), "frequency"),
    ("infinite amplitude", with_(HALF_SPACE, "incident", amplitude=float("inf")), "amplitude"),
]


@pytest.mark.parametrize("name,scenario,key", SIZE_CASES, ids=[c[0] for c in SIZE_CASES])
def test_size_and_numeric_mistakes_raise_value_error(name, scenario, key):
    t0 = time.perf_counter()
    with pytest.raises(ValueError, match=key.replace(".", r"\.")):
        cw.run(scenario)
    took = time.perf_counter() - t0
    assert took < 5.0, f"{name}: {took:.2f} s"
    # the interpreter is alive and runs a normal scenario afterwards
    r = cw.run(with_(HALF_SPACE, "incident", cycles=5))
    assert r.summary["A_inc"] > 0


def test_bar_stack_too_long_and_sweep_too_large_raise(root, tmp_path):
    with pytest.raises(ValueError, match="model.duration"):
        cw.run(_tribobrake(root, tmp_path, "20.0"))
    with pytest.raises(ValueError, match="grid points"):
        cw.sweep(
            os.path.join(root, "examples", "unilateral.toml"),
            {
                "incident.xi": list(range(1, 1_000_001)),
                "interface.static_pressure": [1e5 * k for k in range(1, 11)],
            },
        )


def _tribobrake(root, tmp_path, duration):
    """The Tribobrake example with `model.duration` replaced, as a file path."""
    with open(os.path.join(root, "examples", "tribobrake.toml")) as f:
        text = f.read().replace("duration = 0.2 ", f"duration = {duration} ", 1)
    path = tmp_path / "tribobrake.toml"
    path.write_text(text)
    return str(path)


def test_threads_out_of_range_raise_value_error(root):
    base = os.path.join(root, "examples", "unilateral.toml")
    for n in (0, 100_000):
        with pytest.raises(ValueError, match="threads"):
            cw.sweep(base, {"incident.xi": [0.3]}, threads=n)


def test_missing_file_raises_file_not_found():
    with pytest.raises(FileNotFoundError):
        cw.run("does/not/exist.toml")


def test_ctrl_c_stops_a_long_bar_stack_run_with_keyboard_interrupt(root, tmp_path, monkeypatch):
    monkeypatch.setenv("CONTACTWAVE_MEMORY_BUDGET", "50G")
    scenario = cw.load_scenario(_tribobrake(root, tmp_path, "4.0"))
    timer = threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    t0 = time.perf_counter()
    with pytest.raises(KeyboardInterrupt):
        cw.run(scenario)
    assert time.perf_counter() - t0 < 1.5
    # the next run is not interrupted
    r = cw.run(with_(HALF_SPACE, "incident", cycles=5))
    assert r.summary["A_inc"] > 0


def _failing_identification(tmp_path):
    """An identification whose bounds reach power-law coefficients the solver cannot integrate
    (C up to 1e300; a linear stiffness above 1e24 Pa/m is refused up front): some forward
    runs fail numerically."""
    (tmp_path / "base.toml").write_text(
        '[medium]\nmaterial = "pmma"\n[interface]\nstatic_pressure = 0.1e6\n'
        'compression = { law = "power", c = 1e11, m = 0.5 }\n'
        "[incident]\nfrequency = 1e6\ncycles = 5\nxi = 0.5\n"
        "[solver]\nsamples_per_period = 32\n"
    )
    return {
        "base": "base.toml",
        "observed": ["A2_over_A1"],
        "data": {"incident.xi": [0.3, 0.5, 0.8], "A2_over_A1": [0.01, 0.02, 0.03]},
        "parameter": [
            {
                "key": "interface.compression.c",
                "bounds": [1e10, 1e300],
                "scale": "log",
                "initial": 1e11,
            }
        ],
        "fit": {
            "particles": 4,
            "iterations": 2,
            "local_iterations": 10,
            "local_starts": 1,
            "bootstrap": 0,
        },
    }


def test_identify_with_failed_forward_runs_raises_unless_tolerated(tmp_path):
    # in a child interpreter: the solver's failed Newton iterations leave per-thread state
    # that changes later results in their last bits (a known issue; see the report), and
    # test_sweep.py compares bit for bit with the CLI
    import json
    import subprocess
    import sys

    spec = _failing_identification(tmp_path)
    code = f"""
import json, warnings, contactwave as cw
spec = json.loads({json.dumps(json.dumps(spec))})
file = {str(tmp_path / "id.toml")!r}
try:
    cw.identify(spec, out={str(tmp_path / "out")!r}, file=file)
    raise SystemExit("no SimulationError")
except cw.SimulationError as e:
    msg = str(e)
with warnings.catch_warnings(record=True) as w:
    warnings.simplefilter("always")
    r = cw.identify(spec, file=file, tolerate_failures=True)
print(json.dumps({{"msg": msg, "warned": [str(x.message) for x in w],
                   "failed": r["failed_forward_runs"], "runs": r["forward_runs"],
                   "first": r["first_failure"]}}))
"""
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    res = json.loads(out.stdout.strip().splitlines()[-1])
    assert "forward runs failed" in res["msg"] and "first: row " in res["msg"]
    assert "numerical" in res["msg"]
    # the files are written, as the CLI writes them before exiting 1
    assert (tmp_path / "out" / "identification.json").exists()
    assert any("forward runs failed" in m for m in res["warned"])
    assert 0 < res["failed"] <= res["runs"]
    assert res["first"].startswith("row ")


CHEAP = {
    "medium": {"material": "pmma"},
    "interface": {"static_pressure": 0.1e6, "compression": {"law": "linear", "stiffness": 1e12}},
    "incident": {"frequency": 1e6, "cycles": 2, "xi": 0.5},
    "solver": {"samples_per_period": 16},
}


def test_failed_sweep_points_are_nan_and_all_failed_leaves_only_the_axes():
    # a power law's C of 1e300 cannot be integrated (the gap equation fails; a linear
    # stiffness that large is refused up front)
    base = dict(CHEAP, interface={"static_pressure": 0.1e6,
                                  "compression": {"law": "power", "c": 1e11, "m": 0.5}})
    with pytest.warns(RuntimeWarning, match="1 of 3 sweep points failed"):
        df = cw.sweep(base, {"interface.compression.c": [1e11, 1e300, 1e12]}, as_frame=False)
    assert np.isnan(df["xi"][1]) and np.isfinite(df["xi"][[0, 2]]).all()
    with pytest.warns(RuntimeWarning, match="2 of 2 sweep points failed"):
        df = cw.sweep(base, {"interface.compression.c": [1e299, 1e300]}, as_frame=False)
    assert sorted(df) == ["interface.compression.c", "point"]


def test_a_sweep_over_one_chunk_matches_the_chunked_executor_run():
    # 4100 points: the local sweep runs them 4096 at a time; an executor in 64-point tasks
    from concurrent.futures import ThreadPoolExecutor

    axes = {"incident.xi": np.linspace(0.1, 1.0, 4100)}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        local = cw.sweep(CHEAP, axes, as_frame=False)
        with ThreadPoolExecutor(2) as ex:
            remote = cw.sweep(CHEAP, axes, executor=ex, as_frame=False)
    assert sorted(local) == sorted(remote)
    for k in local:
        np.testing.assert_array_equal(local[k], remote[k], err_msg=k)


def test_ctrl_c_stops_a_million_point_sweep_promptly_with_flat_memory():
    import resource

    before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    for after in (0.3, 3.0):  # during the validation; later, while it runs (or validates)
        timer = threading.Timer(after, lambda: os.kill(os.getpid(), signal.SIGINT))
        timer.start()
        t0 = time.perf_counter()
        with pytest.raises(KeyboardInterrupt):
            cw.sweep(CHEAP, {"incident.xi": np.linspace(0.1, 1.0, 1_000_000)})
        took = time.perf_counter() - t0
        assert took < after + 1.0, f"stopped {took - after:.2f} s after the signal"
    # the models of 10^6 points are never alive at once (kilobytes each: gigabytes)
    grown_mb = (resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - before) / 1024
    assert grown_mb < 600, f"peak memory grew by {grown_mb:.0f} MB"
