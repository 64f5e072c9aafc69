"""The Python API against the CLI's files, input errors, array types, laws and fits."""

import json
import math

import numpy as np
import pytest

import contactwave as cw
from conftest import CHEAP, run_cli

EXAMPLE = "examples/rccm_0.82MPa.toml"


def same(a, b):
    """Equal including NaN (summary.json writes non-finite values as null)."""
    if a is None or b is None:
        return (a is None or (isinstance(a, float) and math.isnan(a))) and (
            b is None or (isinstance(b, float) and math.isnan(b))
        )
    return a == b


@pytest.fixture(scope="module")
def cli_run(cli, root, tmp_path_factory):
    out = tmp_path_factory.mktemp("run")
    run_cli(cli, "run", EXAMPLE, "--out", out)
    return out


@pytest.fixture(scope="module")
def result(root):
    import os

    cwd = os.getcwd()
    os.chdir(root)
    try:
        return cw.run(EXAMPLE)
    finally:
        os.chdir(cwd)


def test_summary_matches_cli(cli_run, result):
    ref = json.loads((cli_run / "summary.json").read_text())
    # the CLI's file ends with its provenance (docs/outputs.md); the in-memory summary not
    assert ref.pop("provenance")["scenario_sha256"]
    assert list(result.summary) == list(ref)
    for k, v in ref.items():
        assert same(result.summary[k], v), k


def load_csv(path):
    return np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)


def test_timeseries_probe_spectrum_match_cli_bit_for_bit(cli_run, result):
    ts = load_csv(cli_run / "timeseries.csv")
    cols = "t,gap,contact_stress,beta,incident_stress,reflected_stress,transmitted_stress"
    for k, name in enumerate(cols.split(",")):
        np.testing.assert_array_equal(getattr(result, name), ts[:, k], err_msg=name)
    pr = load_csv(cli_run / "probe.csv")
    cols = "t,incident_stress,reflected_stress,incident_velocity,reflected_velocity,displacement"
    for k, name in enumerate(cols.split(",")):
        np.testing.assert_array_equal(getattr(result, "probe_" + name), pr[:, k], err_msg=name)
    sp = load_csv(cli_run / "spectrum.csv")
    f, inc, refl = result.spectrum()
    np.testing.assert_array_equal(f, sp[:, 0])
    np.testing.assert_array_equal(inc, sp[:, 1])
    np.testing.assert_array_equal(refl, sp[:, 2])


def test_dtypes_and_shapes(result):
    n = len(result.t)
    m = len(result.probe_t)
    assert n > 100 and m > n
    for name in cw.Result._ARRAYS:
        a = getattr(result, name)
        assert isinstance(a, np.ndarray), name
        assert a.dtype == np.float64 and a.ndim == 1, name
        assert a.flags.c_contiguous, name
        assert a.shape == ((m,) if name.startswith("probe_") else (n,)), name
    assert np.all(np.diff(result.t) > 0)
    assert result.dt == pytest.approx(result.t[1] - result.t[0])
    for a in result.spectrum():
        assert a.dtype == np.float64 and a.shape == result.spectrum().frequency.shape


def test_harmonics_agree_with_summary(result):
    h = result.harmonics()
    s = result.summary
    for n in range(1, 6):
        assert h[f"A{n}_over_Ainc"] == s[f"A{n}_over_Ainc"]
        assert h[f"incident_A{n}"] / h["A_inc"] == s[f"incident_A{n}_over_Ainc"]
    assert h["A2_over_A1"] == s["A2_over_A1"]
    assert h["beta_star"] == s["beta_star"]
    assert h["A1"] > h["A2"] > 0


def test_dict_scenario_equals_file(root, tmp_path):
    from conftest import CHEAP_TOML

    p = tmp_path / "cheap.toml"
    p.write_text(CHEAP_TOML)
    a = cw.run(str(p))
    b = cw.run(CHEAP)
    c = cw.run(cw.scenario_from_dict(CHEAP))
    for k in a.summary:
        if k != "scenario":
            assert same(a.summary[k], b.summary[k]) and same(b.summary[k], c.summary[k]), k
    np.testing.assert_array_equal(a.gap, b.gap)
    assert b.summary["scenario"] == "<dict>"
    # numpy scalars and arrays are accepted
    d = json.loads(json.dumps(CHEAP))
    d["incident"]["xi"] = np.float64(0.35)
    d["solver"]["samples_per_period"] = np.int64(32)
    assert cw.run(d).summary["A2_over_Ainc"] == a.summary["A2_over_Ainc"]


def bad(d, *path_value):
    d = json.loads(json.dumps(d))
    *keys, last = path_value[0].split(".")
    t = d
    for k in keys:
        t = t.setdefault(k, {})
    if path_value[1] is KeyError:
        del t[last]
    else:
        t[last] = path_value[1]
    return d


@pytest.mark.parametrize(
    "key,value,needle",
    [
        ("interface.static_pressure", -1.0, "interface.static_pressure"),
        ("incident.frequency", 0.0, "incident.frequency"),
        ("incident.frequncy", 1e6, "frequncy"),
        ("incident.cycles", "many", "incident.cycles"),
        ("interface.traction", {"law": "rccm", "stiffness": -2e13, "energy": 0.1}, "interface.traction.stiffness"),
        ("interface.traction", {"law": "glue"}, "glue"),
        ("medium.material", "cheese", "medium.material"),
        ("solver.samples_per_period", 3, "solver.samples_per_period"),
        ("incident.xi", None, "incident.xi"),
        ("incident.xi", float("nan"), "incident.xi"),
        ("medium", KeyError, "medium"),
    ],
)
def test_bad_dict_raises_value_error_naming_field(key, value, needle):
    with pytest.raises(ValueError) as e:
        cw.scenario_from_dict(bad(CHEAP, key, value))
    msg = str(e.value)
    assert needle in msg, msg
    assert "<dict>" in msg, msg


def test_bad_file_and_types(tmp_path):
    with pytest.raises(FileNotFoundError):
        cw.load_scenario(tmp_path / "nope.toml")
    p = tmp_path / "bad.toml"
    p.write_text(
        "[medium]\nmaterial = \"pmma\"\n[interface]\nstatic_pressure = -5\n"
        "[incident]\nfrequency = 1e6\namplitude = 1e5\n"
    )
    with pytest.raises(ValueError, match="bad.toml.*interface.static_pressure"):
        cw.load_scenario(p)
    with pytest.raises(TypeError):
        cw.run(42)


def test_law_curve_matches_cli(cli, root, tmp_path):
    run_cli(cli, "law", "examples/power_rccm.toml", "--out", tmp_path)
    ref = load_csv(tmp_path / "law_curve.csv")
    s = cw.load_scenario(root / "examples/power_rccm.toml")
    np.testing.assert_array_equal(cw.law_curve(s, ref[:, 0]), ref[:, 1])
    # any order of the gaps gives the same values
    perm = np.random.default_rng(1).permutation(len(ref))
    np.testing.assert_array_equal(cw.law_curve(s, ref[perm, 0]), ref[perm, 1])


def test_law_curve_from_law_dict():
    law = {
        "static_pressure": 0.1e6,
        "compression": {"law": "linear", "stiffness": 1e12},
        "traction": {"law": "linear", "stiffness": 1e12},
    }
    g = np.array([[-1e-7, 0.0], [1e-8, 2e-7]])
    s = cw.law_curve(law, g)
    assert s.shape == g.shape and s.dtype == np.float64
    uc = 0.1e6 / 1e12
    expect = np.where(g <= uc, -0.1e6 + 1e12 * g, 1e12 * (g - uc))
    np.testing.assert_allclose(s, expect, rtol=1e-12, atol=1e-6)
    with pytest.raises(ValueError, match="interface.traction"):
        cw.law_curve({"static_pressure": 1e5, "traction": {"law": "linear"}}, [0.0])
    # unilateral: rigid compression, free traction
    s = cw.law_curve({"static_pressure": 1e5}, [-1e-9, 0.0, 1e-9])
    np.testing.assert_array_equal(s, [-1e5, -1e5, 0.0])


def test_fit_power_law():
    p = np.array([1e5, 2e5, 5e5, 1e6])
    k = 1.81e10 * p**0.35
    f = cw.fit_power_law(p, k)
    assert set(f) == {"c", "m", "r2"}
    assert f["m"] == pytest.approx(0.35, rel=1e-12)
    assert f["c"] == pytest.approx(1.81e10, rel=1e-9)
    assert f["r2"] == pytest.approx(1.0)
    with pytest.raises(ValueError, match="pressure\\.1"):
        cw.fit_power_law([1e5, -1.0], [1e9, 2e9])


def test_simulation_error_is_runtime_error():
    assert issubclass(cw.SimulationError, RuntimeError)


WEAK = {
    "medium": {"material": "aluminium"},
    "counterpart": {"kind": "medium", "material": "aluminium"},
    "interface": {
        "static_pressure": 10e6,
        "compression": {"law": "power", "c": 1.81e10, "m": 0.35},
    },
    "incident": {"frequency": 5e6, "cycles": 15, "amplitude": 12.2e6},
}


def test_analysis_method_from_python_and_floor_warning():
    """band_peak of a weak harmonic sits on its leakage floor and warns; pulse inversion
    removes the floor of even harmonics (docs/model.md section 6.1)."""
    with pytest.warns(cw.HarmonicFloorWarning):
        band = cw.run(WEAK)
    assert band.analysis_method == "band_peak"
    assert band.summary["analysis_method"] == 0
    assert band.summary["harmonic_floor_warning"] == 1
    assert band.summary["A2_floor_over_Ainc"] > 0.1 * band.summary["A2_over_Ainc"]
    pi = cw.run({**WEAK, "analysis": {"method": "pulse_inversion"}})
    assert pi.analysis_method == "pulse_inversion"
    assert pi.summary["A2_floor_over_Ainc"] == 0.0
    assert pi.floor["A2"] == 0.0
    # the leakage made band_peak's A2 many times larger than the harmonic
    assert band.summary["beta_star"] > 10 * pi.summary["beta_star"]
    with pytest.raises(ValueError, match="analysis"):
        cw.run({**WEAK, "analysis": {"method": "fft"}})
