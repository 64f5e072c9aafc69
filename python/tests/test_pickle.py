"""Every object the package returns pickles (issue 24): run results of every kind
(half-space, shear, oblique, bar stack), the Scenario they hold, sweep tables,
identification results and SimulationError; and a result comes back from a
ProcessPoolExecutor."""

import concurrent.futures as cf
import os
import pickle

import numpy as np

import contactwave as cw

from conftest import CHEAP, ROOT

EXAMPLES = ROOT / "examples"


def same(a, b, where="result"):
    """Equal arrays (bit for bit, NaN included), dicts, lists and plain values."""
    if isinstance(a, np.ndarray):
        assert isinstance(b, np.ndarray) and a.dtype == b.dtype and a.shape == b.shape, where
        assert np.array_equal(a.view(np.uint8), b.view(np.uint8)), where
    elif isinstance(a, dict):
        assert isinstance(b, dict) and list(a) == list(b), where
        for k in a:
            same(a[k], b[k], f"{where}.{k}")
    elif isinstance(a, (list, tuple)):
        assert type(a) is type(b) and len(a) == len(b), where
        for i, (x, y) in enumerate(zip(a, b)):
            same(x, y, f"{where}[{i}]")
    elif isinstance(a, float) and np.isnan(a):
        assert isinstance(b, float) and np.isnan(b), where
    elif isinstance(a, cw.Scenario):
        assert isinstance(b, cw.Scenario), where
        assert (a.to_json(), a.file, a.kind, a.path) == (b.to_json(), b.file, b.kind, b.path)
        assert a.xi == b.xi or (np.isnan(a.xi) and np.isnan(b.xi)), where
    else:
        assert a == b, where


def round_trip(obj):
    back = pickle.loads(pickle.dumps(obj))
    assert type(back) is type(obj)
    return back


def assert_result_round_trips(r):
    back = round_trip(r)
    same(vars(r), vars(back), type(r).__name__)
    return back


def test_scenario_round_trips_and_runs_the_same():
    for s in (cw.load_scenario(EXAMPLES / "rccm_0.82MPa.toml"), cw.scenario_from_dict(CHEAP)):
        back = round_trip(s)
        same(s, back, "scenario")
        same(cw.run(s).summary, cw.run(back).summary, "summary")


def test_half_space_result_round_trips():
    r = cw.run(CHEAP)
    back = assert_result_round_trips(r)
    same(r.spectrum(), back.spectrum(), "spectrum")
    same(r.harmonics(), back.harmonics(), "harmonics")
    assert back.scenario.kind == "half_space"


def test_shear_and_oblique_results_round_trip():
    r = cw.run(EXAMPLES / "shear" / "clipping.toml")
    assert r.shear is not None
    assert_result_round_trips(r)
    r = cw.run(EXAMPLES / "oblique" / "p_45deg.toml")
    assert_result_round_trips(r)


def test_bar_stack_results_round_trip():
    r = cw.run(EXAMPLES / "bar_stack_incident.toml")
    assert isinstance(r, cw.BarStackResult)
    assert_result_round_trips(r)


def test_sweep_tables_identification_and_errors_round_trip():
    cols = cw.sweep(CHEAP, {"incident.xi": [0.2, 0.5]}, as_frame=False)
    same(cols, round_trip(cols), "sweep")
    df = cw.sweep(CHEAP, {"incident.xi": [0.2, 0.5]})
    back = round_trip(df)
    assert back.equals(df) and back.attrs == df.attrs
    err = cw.SimulationError("diverged at step 3")
    back = round_trip(err)
    assert str(back) == str(err) and isinstance(back, RuntimeError)


def test_identification_result_round_trips():
    from test_identify import _spec

    data = {"incident.xi": [0.2, 0.4, 0.6], "A2_over_A1": [0.5, 0.4, 0.3]}
    spec = _spec(data)
    spec["fit"] = {"particles": 2, "iterations": 1, "local_iterations": 2,
                   "local_starts": 1, "bootstrap": 2, "bootstrap_iterations": 1}
    res = cw.identify(spec, tolerate_failures=True)
    same(res, round_trip(res), "identification")


def test_a_result_comes_back_from_a_process_pool():
    path = os.fspath(EXAMPLES / "rccm_0.82MPa.toml")
    here = cw.run(path)
    with cf.ProcessPoolExecutor(1) as ex:
        there = ex.submit(cw.run, path).result()
        scen = ex.submit(cw.load_scenario, path).result()
    same(vars(here), vars(there), "Result")
    same(here.scenario, scen, "scenario")
