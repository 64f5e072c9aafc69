"""Unit strings and plausibility warnings from Python (issue 24 item 3)."""

import warnings

import numpy as np
import pytest

import contactwave as cw


def _dict(frequency, static_pressure, youngs_modulus="5 GPa"):
    return {
        "medium": {"material": "pmma", "youngs_modulus": youngs_modulus},
        "interface": {
            "static_pressure": static_pressure,
            "compression": {"law": "rigid"},
            "traction": {"law": "free"},
        },
        "incident": {"frequency": frequency, "cycles": 5, "xi": 0.35},
        "solver": {"samples_per_period": 100},
    }


def test_unit_strings_give_the_si_run():
    si = cw.run(_dict(1e6, 0.1e6, 5e9))
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # plausible values: no warning
        units = cw.run(_dict("1 MHz", "0.1 MPa", "5 GPa"))
    assert units.summary["A2_over_Ainc"] == si.summary["A2_over_Ainc"]
    assert units.summary["xi"] == pytest.approx(0.35)


def test_a_mismatched_or_unknown_unit_is_a_value_error_naming_the_field():
    with pytest.raises(ValueError, match="incident.frequency"):
        cw.scenario_from_dict(_dict("0.082 MPa", 1e5))
    with pytest.raises(ValueError, match="youngs_modulus"):
        cw.scenario_from_dict(_dict(1e6, 1e5, "71 Gpa"))


def test_sweep_axes_take_unit_strings():
    base = _dict(1e6, 1e5, 5e9)
    a = cw.sweep(base, {"interface.static_pressure": ["50 kPa", "0.1 MPa"]}, as_frame=False)
    b = cw.sweep(base, {"interface.static_pressure": [5e4, 1e5]}, as_frame=False)
    np.testing.assert_array_equal(a["A2_over_Ainc"], b["A2_over_Ainc"])
    with pytest.raises(ValueError, match="static_pressure"):
        cw.sweep(base, {"interface.static_pressure": ["1 MHz"]}, as_frame=False)


def test_a_likely_unit_slip_warns_and_the_run_goes_on():
    s = cw.scenario_from_dict(_dict(1e6, 0.082))  # meant: 0.082 MPa
    assert len(s.warnings) == 1 and "interface.static_pressure" in s.warnings[0]
    with pytest.warns(UserWarning, match="below 1 kPa"):
        r = cw.run(s)
    assert np.isfinite(r.summary["A1_over_Ainc"])
