"""contactwave.analyze: measured records (arrays or files) through the simulator's own
harmonic analysis (docs/model.md section 16)."""
import math
import os
import warnings

import numpy as np
import pytest

import contactwave as cw

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
FIXTURES = os.path.join(ROOT, "crates", "contactwave", "tests", "data", "measured")

F0, DT, N = 2e6, 1e-8, 4096
AMPS = [0.0, 1.0, 2e-2, 5e-3]


def burst(scale=1.0, sign=1.0, dc=0.2, noise=1e-5, seed=0):
    t = np.arange(N) * DT
    s = (t - 15e-6) * F0
    w = np.where((s >= 0) & (s <= 20), np.sin(np.pi * s / 20) ** 2, 0.0)
    x = sum(
        (sign if n % 2 else 1.0) * AMPS[n] * scale**n * np.sin(2 * np.pi * n * F0 * t + 0.3 * n)
        for n in range(1, 4)
    )
    rng = np.random.default_rng(seed)
    return w * x + dc + noise * rng.standard_normal(N)


def test_an_array_gives_its_harmonics():
    a = cw.analyze(burst(), dt=DT, gate=(12e-6, 28e-6, 1e-6))
    assert a.f0_detected and abs(a.f0 - F0) < 2e-3 * F0
    r = a.records[0]
    assert abs(r["A1"] - 1.0) < 1e-3
    assert abs(r["A2_over_A1"] - 2e-2) < 2e-4
    assert abs(r["beta_star"] - r["A2"] / r["A1"] ** 2) < 1e-12
    assert abs(r["dc_offset"] - 0.2) < 1e-3
    assert a.A.shape == (1, 5)


def test_pulse_inversion_and_a_series_fit():
    scales = [0.5, 0.75, 1.0, 1.25]
    plus = np.stack([burst(s, seed=i) for i, s in enumerate(scales)], axis=1)
    minus = [burst(s, sign=-1.0, seed=10 + i) for i, s in enumerate(scales)]
    a = cw.analyze(plus, dt=DT, f0=F0, gate=(12e-6, 28e-6), method="pulse_inversion", inverse=minus, amplitudes=scales)
    assert a.method == "pulse_inversion" and len(a.records) == 4
    assert [r["amplitude"] for r in a.records] == scales
    # A2 = 0.02 A1^2 exactly (quadratic in the drive)
    assert a.fit is not None and abs(a.fit["slope"] / 2e-2 - 1) < 5e-3
    assert a.fit["r_squared"] > 0.999


def test_files_of_every_format_give_the_same_rows():
    rows = []
    for f, kw in [
        ("records.csv", {}),
        ("records.npz", {"datasets": ["echo"]}),
        ("records_v5.mat", {"datasets": ["echo"], "time": "t"}),
        ("records_v73.mat", {"datasets": ["echo"], "time": "t"}),
        ("records.h5", {}),
    ]:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", cw.HarmonicFloorWarning)
            a = cw.analyze(os.path.join(FIXTURES, f), f0=2e6, gate=(1e-6, 9e-6), **kw)
        rows.append(a.A)
    for r in rows[1:]:
        np.testing.assert_allclose(r, rows[0], rtol=1e-12)


def test_bad_input_is_a_value_error():
    with pytest.raises(ValueError, match="complex"):
        cw.analyze(os.path.join(FIXTURES, "complex.npz"))
    with pytest.raises(ValueError, match="uniform time base"):
        cw.analyze(os.path.join(FIXTURES, "gap.csv"))
    with pytest.raises(ValueError, match="dt"):
        cw.analyze(burst())
    with pytest.raises(ValueError, match="--inverse"):
        cw.analyze(burst(), dt=DT, method="pulse_inversion")
    # records of different lengths, a time step and a rate that disagree, a companion the
    # method does not read, a record without content at f0, a gate beyond the record
    with pytest.raises(ValueError, match="as many samples"):
        cw.analyze([burst(), burst()[:100]], dt=DT)
    with pytest.raises(ValueError, match="disagree"):
        cw.analyze(burst(), dt=DT, sample_rate=50e6)
    with pytest.raises(ValueError, match="only with method pulse_inversion"):
        cw.analyze(burst(), dt=DT, inverse=burst(sign=-1.0))
    with pytest.raises(ValueError, match="A1 = 0"):
        cw.analyze(np.zeros(N), dt=DT, f0=F0)
    with pytest.raises(ValueError, match="inside the record"):
        cw.analyze(burst(), dt=DT, gate=(30e-6, 60e-6))


def test_to_pandas():
    pd = pytest.importorskip("pandas")
    a = cw.analyze([burst(1.0), burst(0.5, seed=3)], dt=DT, gate=(12e-6, 28e-6))
    df = a.to_pandas()
    assert isinstance(df, pd.DataFrame) and len(df) == 2 and "A2_over_A1" in df.columns


def test_a_clipped_record_is_marked_and_warns():
    """Issue 56 item 1: a record clipped at 60 % of its peak (an overranged scope)."""
    x = burst(dc=0.0)
    peak = np.max(np.abs(x))
    with pytest.warns(Warning, match="clipped"):
        a = cw.analyze(np.clip(x, -0.6 * peak, 0.6 * peak), dt=DT)
    r = a.records[0]
    assert r["clipped_samples"] > 50 and r["harmonics_reliable"] == 0
    assert abs(r["clip_high"] - 0.6 * peak) < 1e-12
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        clean = cw.analyze(x, dt=DT, gate=(12e-6, 28e-6, 1e-6))
    assert not [w for w in caught if "clipped" in str(w.message)]
    assert clean.records[0]["clipped_samples"] == 0
    with pytest.warns(Warning, match="clipped"):
        cw.analyze(x, dt=DT, full_scale=0.9 * peak)


def test_a_time_column_is_not_a_record():
    """Issue 56 item 3: an array of [t, x] columns."""
    t = np.arange(N) * DT
    with pytest.raises(ValueError, match="time axis"):
        cw.analyze(np.column_stack([t, burst()]), dt=DT)
