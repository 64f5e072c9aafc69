"""``.plot()`` of the result objects and ``cw.plot_sweep`` (matplotlib, Agg backend): the
lines drawn hold the results' own arrays, the harmonic markers sit at n f0, the axes are
labelled with SI units, and a missing matplotlib is an ImportError naming the extra."""

import sys

import numpy as np
import pytest

import contactwave as cw
from conftest import CHEAP

mpl = pytest.importorskip("matplotlib")
mpl.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    plt.close("all")


def lines(ax):
    """The data lines of ``ax`` by label (markers and fits excluded by their labels)."""
    return {ln.get_label(): ln for ln in ax.get_lines() if not ln.get_label().startswith("_")}


def markers(ax, prefix):
    return sorted(
        (ln for ln in ax.get_lines() if (ln.get_gid() or "").startswith(prefix)),
        key=lambda ln: ln.get_gid(),
    )


def test_run_result_signals_and_spectrum_hold_the_results_arrays():
    r = cw.run(CHEAP)
    ax = r.plot()
    got = lines(ax)
    assert set(got) == {"incident", "reflected", "transmitted"}
    for name in got:
        x, y = got[name].get_data()
        assert np.array_equal(x, r.t)
        assert np.array_equal(y, getattr(r, f"{name}_stress"))
    assert ax.get_xlabel() == "time t (s)" and "(Pa)" in ax.get_ylabel()

    fig, (a1, a2) = plt.subplots(1, 2)
    assert r.plot("spectrum", ax=a2) is a2 and not a1.get_lines()
    f, inc, refl = r.spectrum()
    got = lines(a2)
    assert np.array_equal(got["incident"].get_xdata(), f)
    assert np.array_equal(got["incident"].get_ydata(), inc)
    assert np.array_equal(got["reflected"].get_ydata(), refl)
    # the harmonic markers at n f0 (f0 = 1 MHz), n = 1..5
    xs = [m.get_xdata()[0] for m in markers(a2, "harmonic_")]
    assert xs == pytest.approx([1e6, 2e6, 3e6, 4e6, 5e6], rel=1e-12)
    assert a2.get_yscale() == "log" and a2.get_xlabel() == "frequency f (Hz)"

    ax = r.plot("probe")
    assert np.array_equal(lines(ax)["reflected"].get_ydata(), r.probe_reflected_velocity)
    assert np.array_equal(lines(ax)["reflected"].get_xdata(), r.probe_t)
    assert "(m/s)" in ax.get_ylabel()
    with pytest.raises(ValueError, match="kind 'nope'"):
        r.plot("nope")


SMALL_2D = {
    "model": {"kind": "solid_2d", "width": 2e-3, "duration": 0.6e-6, "element_size": 0.1e-3},
    "layer": [{"thickness": 1e-3, "material": "aluminium"}],
    "crack": [{"start": [0.7e-3, 0.5e-3], "end": [1.3e-3, 0.5e-3], "static_pressure": 0.2e6}],
    "source": [
        {
            "x0": 0.6e-3,
            "x1": 1.4e-3,
            "signal": {"frequency": 10e6, "cycles": 2, "amplitude": 10e6, "window": "hann"},
        }
    ],
    "receiver": [{"name": "top", "at": [1e-3, 0.0]}, {"name": "under", "at": [1e-3, 1e-3]}],
}


def test_solid_2d_receivers_and_their_spectrum():
    r = cw.run(SMALL_2D)
    ax = r.plot()
    got = lines(ax)
    assert set(got) == {"top vx", "top vz", "under vx", "under vz"}
    assert np.array_equal(got["under vz"].get_xdata(), r.t)
    assert np.array_equal(got["under vz"].get_ydata(), r.velocity("under", "z"))
    ax = r.plot("spectrum", receivers="under", component="z")
    (line,) = lines(ax).values()
    # the library's spectrum of the record, as cw.analyze gives it
    a = cw.analyze(r.velocity("under", "z"), dt=r.t[1] - r.t[0], t0=r.t[0], f0=10e6)
    assert np.array_equal(line.get_xdata(), a.frequency)
    assert np.array_equal(line.get_ydata(), a.magnitude)
    xs = [m.get_xdata()[0] for m in markers(ax, "harmonic_")]
    assert xs == pytest.approx([1e7, 2e7, 3e7, 4e7, 5e7], rel=1e-12)
    with pytest.raises(ValueError, match="receiver 'nobody'"):
        r.plot(receivers="nobody")


def test_solid_2d_stress_receivers_are_drawn_in_pascals():
    stress = {"name": "s", "at": [0.5e-3, 0.25e-3], "quantity": "stress"}
    # a run with only stress receivers draws them (it once drew an empty panel)
    r = cw.run({**SMALL_2D, "receiver": [stress]})
    ax = r.plot()
    got = lines(ax)
    assert set(got) == {"s sxx", "s szz", "s sxz"}
    assert np.array_equal(got["s szz"].get_ydata(), r.stress("s", "zz"))
    assert ax.get_ylabel() == "stress (Pa)"
    # beside velocity receivers: velocities by default, stresses when named
    r = cw.run({**SMALL_2D, "receiver": SMALL_2D["receiver"] + [stress]})
    assert set(lines(r.plot())) == {"top vx", "top vz", "under vx", "under vz"}
    ax = r.plot("spectrum", receivers="s", component="zz")
    (line,) = lines(ax).values()
    a = cw.analyze(r.stress("s", "zz"), dt=r.t[1] - r.t[0], t0=r.t[0], f0=10e6)
    assert np.array_equal(line.get_ydata(), a.magnitude)
    assert "(Pa s)" in ax.get_ylabel()
    # a stress receiver named beside velocity ones: said so, not "unknown"
    with pytest.raises(ValueError, match="'s' records stress"):
        r.plot("spectrum", receivers=["s", "top"])
    with pytest.raises(ValueError, match="no receivers to plot"):
        cw.run({**SMALL_2D, "receiver": []}).plot()


def test_bar_stack_frf_and_waves(root):
    r = cw.run(root / "examples" / "tribobrake.toml")
    ax = r.plot("frf")
    line = lines(ax)["receptance"]
    assert np.array_equal(line.get_xdata(), r.frf["frequency"])
    assert np.array_equal(line.get_ydata(), np.abs(r.frf["receptance"]), equal_nan=True)
    (mode,) = markers(ax, "first_mode")
    assert mode.get_xdata()[0] == r.summary["first_mode_hz"]
    assert ax.get_xscale() == "log" and ax.get_ylabel() == "receptance |H(f)| (m/N)"
    ax = r.plot("gap")
    assert np.array_equal(lines(ax)["interface 1"].get_ydata(), r.gap[1])
    ax = r.plot("signals")
    assert np.array_equal(lines(ax)["force"].get_ydata(), r.force)
    w = cw.run(root / "examples" / "bar_stack_incident.toml")
    ax = w.plot()
    assert np.array_equal(lines(ax)["reflected"].get_ydata(), w.waves["reflected"])
    assert np.array_equal(lines(ax)["reflected"].get_xdata(), w.t)
    with pytest.raises(ValueError, match="no FRF"):
        w.plot("frf")


F0, DT, N = 2e6, 1e-8, 4096


def burst(scale, seed):
    t = np.arange(N) * DT
    s = (t - 15e-6) * F0
    w = np.where((s >= 0) & (s <= 20), np.sin(np.pi * s / 20) ** 2, 0.0)
    x = scale * np.sin(2 * np.pi * F0 * t) + 0.02 * scale**2 * np.sin(4 * np.pi * F0 * t + 0.3)
    rng = np.random.default_rng(seed)
    return w * x + 0.1 + 1e-5 * rng.standard_normal(N)


def test_analysis_record_spectrum_harmonics_and_fit():
    scales = [0.5, 0.75, 1.0, 1.25]
    records = np.stack([burst(s, i) for i, s in enumerate(scales)], axis=1)
    a = cw.analyze(records, dt=DT, f0=F0, gate=(12e-6, 28e-6), amplitudes=scales)
    # the largest record is shown: the last one (scale 1.25)
    assert a.record == 3
    assert np.allclose(a.t, np.arange(N) * DT, rtol=0, atol=1e-18)
    dc = a.records[3]["dc_offset"]
    assert np.allclose(a.raw, records[:, 3] - dc, rtol=0, atol=1e-15)
    # outside the gate the gated record is zero, inside the taper it is the record
    assert np.all(a.gated[a.t < 12e-6] == 0) and np.all(a.gated[a.t > 28e-6] == 0)
    mid = (a.t > 14e-6) & (a.t < 26e-6)
    assert np.array_equal(a.gated[mid], a.raw[mid])

    ax = a.plot("record")
    got = lines(ax)
    assert np.array_equal(got["gated"].get_ydata(), a.gated)
    assert np.array_equal(got["record (mean removed)"].get_xdata(), a.t)
    assert [m.get_xdata()[0] for m in markers(ax, "gate_")] == [28e-6, 12e-6]  # end, start

    ax = a.plot("spectrum")
    (line,) = lines(ax).values()
    assert np.array_equal(line.get_xdata(), a.frequency)
    assert np.array_equal(line.get_ydata(), a.magnitude)
    # the spectrum peaks at f0 and shows the second harmonic
    k1 = np.argmax(a.magnitude)
    assert abs(a.frequency[k1] - F0) < 2 * (a.frequency[1] - a.frequency[0])
    xs = [m.get_xdata()[0] for m in markers(ax, "harmonic_")]
    assert xs == pytest.approx([F0 * n for n in range(1, 6)], rel=1e-12)

    ax = a.plot("harmonics")
    got = lines(ax)
    assert np.array_equal(got["A_n"].get_ydata(), a.A[3])
    floor = got["floor"].get_ydata()
    assert np.isnan(floor[0])
    assert np.array_equal(floor[1:], [a.records[3][f"A{n}_floor"] for n in range(2, 6)])

    ax = a.plot("fit")
    pts = lines(ax)["A2 of each record"]
    assert np.array_equal(pts.get_xdata(), a.A[:, 0] ** 2)
    assert np.array_equal(pts.get_ydata(), a.A[:, 1])
    (fit,) = [ln for k, ln in lines(ax).items() if k.startswith("A2 = ")]
    x, y = fit.get_data()
    assert np.allclose(y, a.fit["intercept"] + a.fit["slope"] * np.asarray(x), rtol=1e-14)
    # the fit is A2 = 0.02 A1^2 (the records' quadratic term)
    assert abs(a.fit["slope"] / 0.02 - 1) < 5e-3

    single = cw.analyze(burst(1.0, 0), dt=DT, f0=F0)
    with pytest.raises(ValueError, match="no fit"):
        single.plot("fit")


def test_sweep_plot_draws_the_column_against_the_axis():
    pytest.importorskip("pandas")
    xi = np.linspace(0.1, 0.6, 6)
    df = cw.sweep(CHEAP, {"incident.xi": xi, "interface.static_pressure": [0.1e6, 0.2e6]})
    assert df.attrs["axes"] == ["incident.xi", "interface.static_pressure"]
    ax = cw.plot_sweep(df, "A2_over_A1")
    got = lines(ax)
    assert len(got) == 2  # one curve per static pressure
    for p0 in (0.1e6, 0.2e6):
        (line,) = [ln for k, ln in got.items() if k == f"static pressure p0 = {p0:.4g} Pa"]
        rows = df[df["interface.static_pressure"] == p0].sort_values("incident.xi")
        assert np.array_equal(line.get_xdata(), rows["incident.xi"].to_numpy())
        assert np.array_equal(line.get_ydata(), rows["A2_over_A1"].to_numpy())
    assert ax.get_xlabel() == "load ratio xi" and ax.get_ylabel() == "A2 / A1"
    # the dict of arrays too, and the other axis as x
    d = cw.sweep(CHEAP, {"interface.static_pressure": [0.1e6, 0.2e6, 0.3e6]}, as_frame=False)
    ax = cw.plot_sweep(d, "A2_over_Ainc")
    (line,) = ax.get_lines()
    assert np.array_equal(line.get_xdata(), d["interface.static_pressure"])
    assert np.array_equal(line.get_ydata(), d["A2_over_Ainc"])
    assert ax.get_xlabel() == "static pressure p0 (Pa)"
    with pytest.raises(ValueError, match="'nope'"):
        cw.plot_sweep(d, "nope")


def test_identification_plot_shows_the_data_and_the_fitted_curve():
    xi = [0.2, 0.4, 0.6, 0.8]
    base = dict(CHEAP)
    base["interface"] = {
        "static_pressure": 0.1e6,
        "traction": {"law": "rccm", "stiffness": 2e13, "energy": 1e3},
    }
    truth = cw.sweep(base, {"incident.xi": xi}, as_frame=False)["A2_over_A1"]
    spec = {
        "base": "<unused>",
        "data": {"incident.xi": xi, "A2_over_A1": list(truth * [1.01, 0.99, 1.0, 1.005])},
        "observed": ["A2_over_A1"],
        "parameter": [{"key": "interface.traction.stiffness", "bounds": [1e11, 1e15],
                       "scale": "log", "initial": 1e13}],
        "fit": {"particles": 0, "local_iterations": 20, "local_starts": 1, "bootstrap": 0},
    }
    import json
    import tempfile
    import os

    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "base.json.toml")
        _write_toml(path, base)
        spec["base"] = path
        res = cw.identify(spec)
    assert isinstance(res, dict) and isinstance(res, cw.Identification)
    assert res.conditions == ["incident.xi"] and res.observed == ["A2_over_A1"]
    t = res.fit_table
    assert np.array_equal(t["incident.xi"], xi)
    assert np.allclose(t["A2_over_A1"], spec["data"]["A2_over_A1"], rtol=1e-15)
    # the fitted column is the model at the estimate: close to the noise-free curve
    assert np.allclose(t["fitted_A2_over_A1"], truth, rtol=0.03)
    ax = res.plot()
    got = lines(ax)
    fitted = got["fitted"]
    assert np.array_equal(fitted.get_xdata(), t["incident.xi"])
    assert np.array_equal(fitted.get_ydata(), t["fitted_A2_over_A1"])
    (bars,) = ax.containers  # the errorbar: points and 1-sigma bars
    assert bars.get_label() == "measured"
    assert np.array_equal(bars.lines[0].get_xdata(), t["incident.xi"])
    assert np.array_equal(bars.lines[0].get_ydata(), t["A2_over_A1"])
    (caps,) = bars.lines[2]  # the bars' segments: y -+ sigma
    seg = np.array(caps.get_segments())
    assert np.allclose(seg[:, 1, 1] - seg[:, 0, 1], 2 * t["sigma_A2_over_A1"], rtol=1e-12)
    assert ax.get_xlabel() == "load ratio xi" and ax.get_ylabel() == "A2 / A1"
    # pickles with its table
    import pickle

    back = pickle.loads(pickle.dumps(res))
    assert back == res and np.array_equal(back.fit_table["fitted_A2_over_A1"], t["fitted_A2_over_A1"])
    assert json.loads(json.dumps(dict(back)))["estimates"] == res["estimates"]


def _write_toml(path, d):
    """A scenario dict with scalar and inline-table values as TOML."""

    def val(v):
        if isinstance(v, dict):
            return "{ " + ", ".join(f"{k} = {val(x)}" for k, x in v.items()) + " }"
        if isinstance(v, str):
            return f'"{v}"'
        return repr(float(v)) if isinstance(v, float) else repr(v)

    with open(path, "w") as f:
        for section, table in d.items():
            f.write(f"[{section}]\n")
            for k, v in table.items():
                f.write(f"{k} = {val(v)}\n")


def test_a_missing_matplotlib_is_an_import_error_naming_the_extra(monkeypatch):
    r = cw.run(CHEAP)
    monkeypatch.setitem(sys.modules, "matplotlib.pyplot", None)
    with pytest.raises(ImportError, match=r"contactwave\[plot\]"):
        r.plot()


def test_the_analysis_picture_is_the_cli_spectrum(cli, root, tmp_path):
    # one analysis, one spectrum: Analysis.frequency/magnitude are spectrum.csv of
    # `contactwave analyze` on the same file
    import csv
    import warnings

    from conftest import run_cli

    path = root / "crates" / "contactwave" / "tests" / "data" / "measured" / "records.csv"
    run_cli(cli, "analyze", path, "--f0", "2e6", "--gate", "1e-6,9e-6", "--out", tmp_path / "a")
    with open(tmp_path / "a" / "spectrum.csv") as f:
        rows = [r for r in csv.reader(line for line in f if not line.startswith("#"))]
    spec = np.array([[float(v) for v in r] for r in rows[1:]])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", cw.HarmonicFloorWarning)
        a = cw.analyze(path, f0=2e6, gate=(1e-6, 9e-6))
    assert rows[0] == ["frequency", "magnitude"]
    np.testing.assert_allclose(a.frequency, spec[:, 0], rtol=1e-15)
    np.testing.assert_allclose(a.magnitude, spec[:, 1], rtol=1e-15)
    assert len(a.t) == len(a.raw) == len(a.gated) > 0


# issue 56 item 10: what a spectrum plot and its axes tell a researcher


def test_harmonic_markers_come_from_the_scenarios_f0_in_si():
    # a frequency written as a unit string is the scenario's f0 (not the detected one)
    half = {**CHEAP, "incident": {**CHEAP["incident"], "frequency": "1 MHz"}}
    ax = cw.run(half).plot("spectrum")
    xs = [m.get_xdata()[0] for m in markers(ax, "harmonic_")]
    assert xs == pytest.approx([1e6, 2e6, 3e6, 4e6, 5e6], rel=1e-12)
    source = dict(SMALL_2D["source"][0])
    source["signal"] = {**source["signal"], "frequency": "10 MHz"}
    r = cw.run({**SMALL_2D, "source": [source]})
    ax = r.plot("spectrum", receivers="under", component="z")
    xs = [m.get_xdata()[0] for m in markers(ax, "harmonic_")]
    assert xs == pytest.approx([1e7, 2e7, 3e7, 4e7, 5e7], rel=1e-12)


def _above_dc(frequency, *magnitudes):
    """The smallest and largest positive magnitude of the bins above 0 Hz."""
    keep = np.asarray(frequency) > 0
    v = np.concatenate([np.asarray(m)[keep] for m in magnitudes])
    v = v[np.isfinite(v) & (v > 0)]
    return v.min(), v.max()


def test_the_spectrum_log_axis_spans_the_bins_above_the_dc_bin():
    r = cw.run(CHEAP)
    f, inc, refl = r.spectrum()
    ax = r.plot("spectrum")
    lo, hi = _above_dc(f, inc, refl)
    bottom, top = ax.get_ylim()
    assert bottom == pytest.approx(lo / 10**0.1, rel=1e-9)
    assert top == pytest.approx(hi * 10**0.1, rel=1e-9)
    r2 = cw.run(SMALL_2D)
    ax = r2.plot("spectrum", receivers="under", component="z")
    a = cw.analyze(r2.velocity("under", "z"), dt=r2.t[1] - r2.t[0], t0=r2.t[0], f0=10e6)
    assert a.frequency[0] == 0.0
    lo, hi = _above_dc(a.frequency, a.magnitude)
    assert ax.get_ylim()[0] == pytest.approx(lo / 10**0.1, rel=1e-9)
    # the DC bin, rounding once the mean is removed, lies below the axis
    assert a.magnitude[0] < ax.get_ylim()[0]
    records = np.stack([burst(1.0, 0), burst(0.5, 1)], axis=1)
    m = cw.analyze(records, dt=DT, f0=F0)
    ax = m.plot("spectrum")
    lo, hi = _above_dc(m.frequency, m.magnitude)
    assert ax.get_ylim() == pytest.approx((lo / 10**0.1, hi * 10**0.1), rel=1e-9)


def test_tick_labels_carry_the_axis_unit_with_its_prefix():
    def tick(axis, value):
        return axis.get_major_formatter()(value, 0)

    r = cw.run(CHEAP)
    ax = r.plot("probe")
    # an axis in m/s: "300 mm/s", not "300 m" (metres)
    assert tick(ax.yaxis, 0.3) == "300 mm/s"
    assert tick(ax.xaxis, 5e-6) == "5 µs"
    assert tick(r.plot().yaxis, 2e6) == "2 MPa"
    assert tick(r.plot("gap").yaxis, 2e-8) == "20 nm"
    assert tick(r.plot("spectrum").xaxis, 2e6) == "2 MHz"
    # the labels drawn carry the unit too
    fig = ax.figure
    fig.canvas.draw()
    drawn = [t.get_text() for t in ax.get_yticklabels() if t.get_text()]
    assert drawn and all(t.endswith("m/s") for t in drawn), drawn
    r2 = cw.run({**SMALL_2D, "receiver": [{"name": "s", "at": [0.5e-3, 0.25e-3],
                                           "quantity": "stress"}]})
    ax = r2.plot()
    assert tick(ax.yaxis, 3e6) == "3 MPa" and tick(ax.xaxis, 2e-7) == "200 ns"
    ax = cw.run(SMALL_2D).plot()
    assert tick(ax.yaxis, 0.3) == "300 mm/s"
