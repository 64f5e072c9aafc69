"""Timings of the Python bindings (docs/performance.md, section "Python"):

1. overhead of ``cw.run`` over the Rust ``simulate`` alone (``cw._bench_simulate``), on the
   chapter-3 RCCM scenario of ``contactwave bench`` (medians of --runs runs, 1 thread);
2. a 10 000-point xi sweep of a cheap scenario (3 cycles, 32 samples per period) on all
   local cores and on a 2-worker Dask LocalCluster (points per second).

    python examples/python/bench.py [--runs 200] [--points 10000] [--no-dask]
"""

import argparse
import os
import statistics
import time

import numpy as np

import contactwave as cw

RCCM = {
    "medium": {"material": "pmma"},
    "interface": {
        "static_pressure": 0.082e6,
        "traction": {"law": "rccm", "stiffness": 2e13, "energy": 0.1, "viscosity": 1e-8},
    },
    "incident": {"frequency": 1e6, "cycles": 15, "amplitude": 0.82e6},
    "probe": {"x": -0.03},
}

CHEAP = {
    "medium": {"material": "pmma"},
    "interface": {"static_pressure": 0.1e6},
    "incident": {"frequency": 1e6, "cycles": 3, "xi": 0.35},
    "solver": {"samples_per_period": 32},
}


def overhead(runs: int) -> None:
    s = cw.scenario_from_dict(RCCM)
    cw.run(s)
    cw._bench_simulate(s, 5)
    # interleave the two so that load from elsewhere hits both alike
    py_t, rs_t = [], []
    for _ in range(runs):
        t0 = time.perf_counter()
        cw.run(s)
        py_t.append(time.perf_counter() - t0)
        rs_t.append(cw._bench_simulate(s, 1)[0])
    py_m, rs_m = statistics.median(py_t), statistics.median(rs_t)
    print(f"cw.run (RCCM 0.82 MPa, 15 cycles): median {py_m * 1e3:.3f} ms over {runs} runs")
    print(f"Rust simulate alone:               median {rs_m * 1e3:.3f} ms")
    print(f"Python overhead:                   {(py_m / rs_m - 1) * 100:+.1f} %"
          f" ({(py_m - rs_m) * 1e6:.0f} us per call)")


def sweeps(points: int, dask: bool) -> None:
    axes = {"incident.xi": np.linspace(0.05, 1.2, points)}
    cw.sweep(CHEAP, {"incident.xi": [0.3]})
    t0 = time.perf_counter()
    local = cw.sweep(CHEAP, axes)
    t = time.perf_counter() - t0
    print(f"{points}-point sweep, local ({os.cpu_count()} cores): {t:.2f} s, {points / t:.0f} points/s")
    if not dask:
        return
    from dask.distributed import Client, LocalCluster

    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                      dashboard_address=None) as cluster, Client(cluster) as client:
        cw.sweep(CHEAP, {"incident.xi": [0.3, 0.4]}, executor=client)  # warm the workers
        t0 = time.perf_counter()
        remote = cw.sweep(CHEAP, axes, executor=client)
        t = time.perf_counter() - t0
    same = all(
        np.array_equal(local[c].to_numpy(), remote[c].to_numpy(), equal_nan=True)
        for c in local.columns
    )
    print(f"{points}-point sweep, Dask LocalCluster(2 workers x 1 thread): {t:.2f} s, "
          f"{points / t:.0f} points/s, identical to local: {same}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=200)
    ap.add_argument("--points", type=int, default=10_000)
    ap.add_argument("--no-dask", action="store_true")
    a = ap.parse_args()
    overhead(a.runs)
    sweeps(a.points, not a.no_dask)


if __name__ == "__main__":
    main()
