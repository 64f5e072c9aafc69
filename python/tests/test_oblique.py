"""Oblique incidence from Python (docs/model.md section 14): `incident.angle` in a dict, the
outgoing P and SV waves at Snell's angles, their energy closure, and a sweep over the angle."""

import math
import warnings

import numpy as np
import pytest

import contactwave as cw

AL = {"E": 71e9, "rho": 2710.0, "nu": 0.33}
STEEL_MATERIAL = "steel"


def oblique(angle, method="pulse_inversion"):
    """A P wave on a pressed power-law contact with friction, aluminium on steel."""
    return {
        "medium": {"material": "aluminium"},
        "counterpart": {"kind": "medium", "material": STEEL_MATERIAL},
        "interface": {
            "static_pressure": 0.3e6,
            "compression": {"law": "power", "c": 1.81e10, "m": 0.35},
            "tangential": {"law": "coulomb", "friction": 0.3},
        },
        "incident": {"angle": angle, "frequency": 1e6, "cycles": 10, "amplitude": 1e6},
        "solver": {"samples_per_period": 40},
        "analysis": {"method": method},
    }


WAVES = ("reflected_P", "reflected_SV", "transmitted_P", "transmitted_SV")


def speeds(material):
    """(c_L, c_T) of a preset in a half-space: sqrt(M/rho) with the P-wave modulus
    M = E (1 - nu) / ((1 + nu) (1 - 2 nu)), and sqrt(G/rho)."""
    e, rho, nu = material["E"], material["rho"], material["nu"]
    m = e * (1 - nu) / ((1 + nu) * (1 - 2 * nu))
    return math.sqrt(m / rho), math.sqrt(e / (2 * (1 + nu)) / rho)


def test_run_gives_snell_angles_and_closes_the_energy_of_the_waves():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", cw.HarmonicFloorWarning)
        r = cw.run(oblique(30.0))
    s = r.summary
    assert s["angle"] == pytest.approx(30.0)
    # Snell: the horizontal slowness p = sin(theta_w) / c_w is that of the incident P wave
    cl1, ct1 = speeds(AL)
    p = math.sin(math.radians(30.0)) / cl1
    assert s["slowness"] == pytest.approx(p, rel=1e-12)
    assert s["reflected_P_angle"] == pytest.approx(30.0, rel=1e-12)
    assert math.sin(math.radians(s["reflected_SV_angle"])) == pytest.approx(p * ct1, rel=1e-12)
    for w in ("transmitted_P", "transmitted_SV"):
        # a slower wave leaves closer to the normal
        assert 0 < s[f"{w}_angle"] < 90
    cl2 = math.sin(math.radians(s["transmitted_P_angle"])) / p
    ct2 = math.sin(math.radians(s["transmitted_SV_angle"])) / p
    # steel's P wave is slower than aluminium's (6001 against 6230 m/s), its S wave faster
    assert ct2 < cl2 < cl1 and ct2 > ct1
    # energy: incident = the four waves + what the interface keeps or dissipates
    out = sum(s[f"energy_{w}"] for w in WAVES)
    assert s["energy_wave_incident"] > 0
    assert 0 < out < s["energy_wave_incident"]
    kept = s["energy_stored_end"] + s["energy_damage"] + s["friction_dissipation"]
    assert (s["energy_wave_incident"] - out - kept) / s["energy_wave_incident"] == pytest.approx(
        0.0, abs=1e-6
    )
    assert s["energy_closure_error"] < 1e-6
    fractions = sum(s[f"energy_{w}_fraction"] for w in WAVES)
    assert fractions == pytest.approx(out / s["energy_wave_incident"], rel=1e-12)
    # mode conversion: every outgoing wave is there, with a second harmonic of its own
    for w in WAVES:
        assert s[f"{w}_A1_over_Ainc"] > 1e-3
        assert s[f"{w}_A2_over_A1"] > 0


def test_sweep_over_the_angle():
    angles = [0.0, 15.0, 30.0, 45.0]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", cw.HarmonicFloorWarning)
        df = cw.sweep(oblique(0.0), {"incident.angle": angles}, threads=2, as_frame=False)
    assert list(df["incident.angle"]) == angles
    assert np.allclose(df["angle"], angles)
    # at 0 degrees a P wave converts into nothing: no SV waves
    assert df["reflected_SV_A1_over_Ainc"][0] == 0.0
    assert df["energy_reflected_SV"][0] < 1e-12 * df["energy_wave_incident"][0]
    # beyond it, mode conversion grows with the angle over this range
    sv = np.asarray(df["energy_reflected_SV_fraction"])
    assert np.all(np.diff(sv) > 0)
    assert np.all(np.asarray(df["energy_closure_error"]) < 1e-6)
    # each point is the run of the same scenario
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", cw.HarmonicFloorWarning)
        one = cw.run(oblique(30.0)).summary
    assert df["reflected_P_A2_over_A1"][2] == pytest.approx(one["reflected_P_A2_over_A1"], rel=1e-12)


def test_angle_beyond_the_critical_one_is_an_error():
    # an SV wave beyond asin(c_T / c_L) of aluminium (30.2 degrees), aluminium on aluminium:
    # the reflected P wave would be evanescent
    s = oblique(0.0)
    s["counterpart"]["material"] = "aluminium"
    del s["incident"]
    s["shear_incident"] = {"angle": 50.0, "frequency": 1e6, "cycles": 5, "amplitude": 1e6}
    cl, ct = speeds(AL)
    critical = math.degrees(math.asin(ct / cl))
    with pytest.raises(ValueError, match=r"shear_incident\.angle.*%.6f" % critical):
        cw.run(s)


def test_oblique_keys_are_over_the_incident_wave_and_repr_shows_the_waves():
    """Issue 24 item 5: `amplitude` and `A_inc` are the incident wave's, the interface
    components are named (`reflected_normal_*`, ...), `harmonics()` agrees with the summary,
    and the repr shows the outgoing waves."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", cw.HarmonicFloorWarning)
        r = cw.run(oblique(45.0))
    s = r.summary
    c_l, _ = speeds(AL)
    assert s["amplitude"] == 1e6
    assert s["A_inc"] == pytest.approx(1e6 / (AL["rho"] * c_l), rel=1e-3)
    assert s["incident_A1_over_Ainc"] == pytest.approx(1.0, abs=0.01)
    for gone in ("A1_over_Ainc", "shear_A1_over_Ainc", "wave_A_inc", "shear_A_inc"):
        assert gone not in s
    h = r.harmonics()
    assert h["A_inc"] == pytest.approx(s["A_inc"], rel=1e-12)
    assert h["A1_over_Ainc"] == pytest.approx(s["reflected_normal_A1_over_Ainc"], rel=1e-12)
    text = repr(r)
    assert "reflected_P_A1_over_Ainc" in text and "angle=45" in text


def test_oblique_floor_warning_names_the_normal_component():
    """The floor warning at oblique incidence reads the renamed component keys."""
    with pytest.warns(cw.HarmonicFloorWarning, match="reflected_normal_A"):
        cw.run(oblique(45.0, method="band_peak"))
