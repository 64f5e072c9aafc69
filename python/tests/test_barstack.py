"""Bar stacks from Python (`cw.run_bar_stack`, and `cw.run` on a bar-stack file): the
Tribobrake hammer test and an incident-wave run, numpy results, errors naming the field."""

import os

import numpy as np
import pytest

import contactwave as cw

EXAMPLES = os.path.join(os.path.dirname(__file__), "..", "..", "examples")


def test_tribobrake_hammer_test_from_a_file():
    r = cw.run(os.path.join(EXAMPLES, "tribobrake.toml"))
    assert isinstance(r, cw.BarStackResult)
    # thesis chapter 4: the mass-spring mode between 780 and 900 Hz, closed contacts
    assert 780.0 <= r.summary["first_mode_hz"] <= 900.0
    assert r.summary["min_contact_pressure"] > 0.0
    n = len(r.t)
    assert r.gap.shape == (2, n) and r.pressure.shape == (2, n)
    assert r.displacement.dtype == np.float64 and r.displacement.shape == (n,)
    # the static step: p0 = m g / S at the guide/sample interface
    assert r.static_pressure[0] == pytest.approx(1.61 * 9.81 / 1.15e-4, rel=1e-9)
    # the pressure history starts at p0
    assert r.pressure[0, 0] == pytest.approx(r.static_pressure[0], rel=1e-9)
    assert r.waves is None
    assert r.frf["receptance"].shape == r.frf["frequency"].shape
    # the FRF is masked (NaN) where the force spectrum is below -40 dB of its peak (the
    # zeros of the half-sine at 1.32, 2.20 kHz...): the largest receptance below 5 kHz is
    # the first mode, not a division by almost nothing
    f, h = r.frf["frequency"], r.frf["receptance"]
    masked = ~(r.frf["force_db"] >= -40.0)
    assert masked.any() and np.array_equal(np.isnan(h), masked)
    assert np.array_equal(np.isnan(r.frf["accelerance"]), masked)
    band = f < 5e3
    assert f[band][np.nanargmax(h[band])] == pytest.approx(r.summary["first_mode_hz"], rel=0.01)


def tribobrake_dict(compression, peak):
    law = {"between": ["guide", "sample"], "compression": compression, "traction": {"law": "free"}}
    return {
        "model": {"kind": "bar_stack", "area": 1.15e-4, "gravity": 9.81, "duration": 0.2},
        "segment": [
            {"name": "guide", "length": 0.229, "material": "aluminium", "mass": 1.61},
            {"name": "sample", "length": 0.015, "material": "aluminium"},
        ],
        "interface": [law, dict(law, between=["sample", "obstacle"])],
        "excitation": {"kind": "force_pulse", "peak": peak},
    }


def test_linear_tribobrake_frf_peaks_at_the_first_mode():
    # a constant 8.5e11 Pa/m: about 840 Hz (lumped estimate), no second harmonic
    r = cw.run_bar_stack(tribobrake_dict({"law": "linear", "stiffness": 8.5e11}, 9.0))
    f1 = r.summary["first_mode_hz"]
    assert 800.0 <= f1 <= 880.0
    assert r.summary["A2_over_A1"] < 1e-3
    f = r.frf["frequency"]
    # below the first zero of the 1.135 ms half-sine's spectrum (1.32 kHz), where the H1
    # estimate does not hold
    band = (f > 300.0) & (f < 1250.0)
    f_peak = f[band][np.argmax(r.frf["receptance"][band])]
    assert f_peak == pytest.approx(f1, rel=0.01)


def test_incident_wave_run_from_a_dict():
    d = {
        "model": {
            "kind": "bar_stack",
            "area": 1.0,
            "static_force": 0.1e6,
            "first_end": "transparent",
            "last_end": "obstacle",
        },
        "segment": [{"name": "bar", "length": 0.005, "material": "pmma"}],
        "interface": [
            {
                "between": ["bar", "obstacle"],
                "compression": {"law": "rigid"},
                "traction": {"law": "free"},
            }
        ],
        "incident": {"frequency": 1e6, "cycles": 15, "xi": 0.35},
        "probe": [{"name": "mid", "x": 0.0025}],
    }
    r = cw.run(d)
    assert isinstance(r, cw.BarStackResult)
    # the same problem by the exact half-space solver (unilateral contact, rigid wall)
    h = cw.run(
        {
            "medium": {"material": "pmma"},
            "interface": {"static_pressure": 0.1e6},
            "incident": {"frequency": 1e6, "cycles": 15, "xi": 0.35},
        }
    )
    for key in ("A1_over_Ainc", "A2_over_Ainc"):
        assert r.summary[key] == pytest.approx(h.summary[key], rel=0.01)
    assert set(r.waves) == {"incident", "reflected"}
    assert r.waves["reflected"].shape == r.t.shape
    assert len(r.frf["frequency"]) == 0
    assert r.probes["mid"]["x"] == 0.0025
    assert r.probes["mid"]["stress"].shape == r.t.shape


def test_bad_bar_stack_names_the_field():
    d = {
        "model": {"kind": "bar_stack", "area": 1.0, "first_end": "free", "last_end": "free"},
        "segment": [{"name": "bar", "length": 0.005, "material": "pmma"}],
        "incident": {"frequency": 1e6, "amplitude": 1e5},
    }
    with pytest.raises(ValueError, match="model.first_end"):
        cw.run_bar_stack(d, file="mine.toml")
    with pytest.raises(ValueError, match="mine.toml"):
        cw.run_bar_stack(d, file="mine.toml")
    with pytest.raises(FileNotFoundError):
        cw.run_bar_stack(os.path.join(EXAMPLES, "nope.toml"))


def test_bar_stack_sweep_locally_and_on_an_executor():
    from concurrent.futures import ThreadPoolExecutor

    path = os.path.join(EXAMPLES, "tribobrake.toml")
    axes = {"excitation.peak": [9.0, 32.0]}
    local = cw.sweep(path, axes, threads=2, as_frame=False)
    f = local["first_mode_hz"]
    # thesis chapter 4: the first mode falls with the force (modified power law)
    assert f[1] < f[0] and 780.0 <= f[1] <= 900.0
    with ThreadPoolExecutor(2) as ex:
        remote = cw.sweep(path, axes, ex, chunk_size=1, as_frame=False)
    assert np.array_equal(remote["first_mode_hz"], f)
    assert np.array_equal(remote["min_contact_pressure"], local["min_contact_pressure"])


def test_shear_burst_through_a_frictional_stack():
    """A shear burst through two aluminium bars pressed at 10 MPa with rigid-stick Coulomb
    friction (mu p0 / tau_inc = 0.6): the transmitted shear stress is clipped at mu p0, so
    the interface slips, dissipates, and its contact shear stress never exceeds mu p0."""
    r = cw.run(os.path.join(EXAMPLES, "shear", "bar_stack_clipping.toml"))
    sh = r.shear
    assert sh is not None and sh["waves"] is not None
    tau = np.asarray(sh["stress"])[0]
    mu_p0 = 0.3 * 10e6
    assert np.max(np.abs(tau)) <= mu_p0 * (1 + 1e-9)
    assert np.max(np.abs(tau)) > 0.99 * mu_p0
    assert sh["friction_dissipation"][0] > 0
    assert r.summary["friction_dissipation"] == pytest.approx(sum(sh["friction_dissipation"]))
    # the shear waves have the time grid of every other series
    assert sh["waves"]["reflected"].shape == r.t.shape
    assert r.summary["energy_closure_error"] < 1e-5
