"""Shear waves and friction from Python (docs/model.md section 13): numpy arrays of the
tangential histories, the clipping law, sweeps over the tangential keys, input errors."""

import math

import numpy as np
import pytest

import contactwave as cw

CLIP = {
    "medium": {"material": "aluminium"},
    "counterpart": {"kind": "medium", "material": "aluminium"},
    "interface": {
        "static_pressure": 10e6,
        "tangential": {"law": "coulomb", "friction": 0.3},
    },
    "shear_incident": {
        "frequency": 1e6,
        "cycles": 5,
        "window": "rectangular",
        "amplitude": 5e6,
    },
}


def test_clipping_arrays_and_summary():
    r = cw.run(CLIP)
    sh = r.shear
    assert sh is not None
    for k in ("shear_gap", "slip", "shear_stress", "friction_limit", "shear_transmitted_stress"):
        assert isinstance(sh[k], np.ndarray) and sh[k].dtype == np.float64
        assert sh[k].shape == r.t.shape
    # rigid-stick Coulomb between identical media: tau_tr = tau_inc clipped at +-mu p0
    clip = np.clip(sh["shear_incident_stress"], -3e6, 3e6)
    assert np.max(np.abs(sh["shear_transmitted_stress"] - clip)) < 1e-6 * 5e6
    s = r.summary
    assert s["friction_ratio"] == pytest.approx(0.6)
    assert s["friction_dissipation"] > 0
    assert s["energy_closure_error"] < 1e-9
    # a shear wave alone: no longitudinal harmonic keys
    assert "A1_over_Ainc" not in s


def test_sweep_over_friction_coefficient():
    df = cw.sweep(CLIP, {"interface.tangential.friction": [0.1, 0.3, 2.0]})
    assert list(df["interface.tangential.friction"]) == [0.1, 0.3, 2.0]
    d = df["friction_dissipation"].to_numpy()
    # mu = 2: mu p0 / tau = 4, the interface sticks: no dissipation
    assert d[2] == 0.0 and d[0] > 0 and d[1] > 0


def test_malformed_tangential_input_raises():
    bad = {**CLIP, "interface": {"static_pressure": 10e6, "tangential": {"law": "coulomb", "friction": -0.3}}}
    with pytest.raises(ValueError, match="interface.tangential.friction"):
        cw.run(bad)
    no_shear_modulus = {
        **CLIP,
        "medium": {"youngs_modulus": 71e9, "density": 2710.0},
    }
    with pytest.raises(ValueError, match="medium.poisson_ratio"):
        cw.run(no_shear_modulus)
