"""``contactwave.identify``: a quick synthetic round trip (RCCM stiffness from A2/A1
versus xi) and invalid input."""

import csv

import pytest

import contactwave as cw

from conftest import ROOT


def _spec(data):
    return {
        "base": str(ROOT / "examples" / "rccm_0.82MPa.toml"),
        "data": data,
        "observed": ["A2_over_A1"],
        "set": {
            "interface.traction.energy": 1e3,
            "interface.traction.viscosity": 0.0,
            "solver.samples_per_period": 100,
        },
        "parameter": [
            {
                "key": "interface.traction.stiffness",
                "bounds": [1e8, 1e17],
                "scale": "log",
                "initial": 1e12,
            }
        ],
        "fit": {"particles": 4, "iterations": 3, "local_iterations": 30,
                "local_starts": 1, "bootstrap": 3, "bootstrap_iterations": 5},
    }


def test_identify_recovers_stiffness_from_committed_synthetic_data(tmp_path):
    # the example's data: C_N = 2e13 Pa/m with 1% noise
    path = ROOT / "examples" / "identify" / "rccm_undamaged.csv"
    with open(path) as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    data = {
        "incident.xi": [float(r["incident.xi"]) for r in rows],
        "A2_over_A1": [float(r["A2_over_A1"]) for r in rows],
    }
    res = cw.identify(_spec(data), out=tmp_path / "out")
    key = "interface.traction.stiffness"
    est = res["estimates"][key]
    assert abs(est / 2e13 - 1) < 0.05
    lo, hi = res["intervals"][key]
    assert lo < est < hi
    assert res["verdicts"][key].startswith("identified")
    assert res["forward_runs"] > 0
    assert (tmp_path / "out" / "identification.json").is_file()
    assert (tmp_path / "out" / "identification.html").is_file()


def test_identify_rejects_negative_amplitudes():
    data = {"incident.xi": [0.1, 0.2], "A2_over_A1": [0.5, -1.0]}
    with pytest.raises(ValueError, match="A2_over_A1"):
        cw.identify(_spec(data))


def test_identify_from_raw_records_in_a_dict():
    # issue 28 item 2: the records of examples/identify/raw_records.toml (eight echoes
    # behind a 2 MHz transducer, 0.1% noise, C_N = 2e13 Pa/m) given as [records] in a
    # dict; the forward echoes are reduced by the same analysis through the same
    # transducer
    ex = ROOT / "examples" / "identify"
    spec = _spec(None)
    del spec["data"]
    spec["records"] = {
        "files": [str(ex / "raw_records.csv")],
        "condition": "incident.xi",
        "values": [0.1, 0.2, 0.3, 0.45, 0.6, 0.8, 1.0, 1.3],
        "waveform": "reflected_velocity",
        "gate": [1.2e-5, 3.2e-5, 2e-6],
        "band_pass": {"centre": 2e6, "q": 1.0},
    }
    res = cw.identify(spec)
    cn = res["estimates"]["interface.traction.stiffness"]
    assert abs(cn / 2e13 - 1) < 0.05, cn
    lo, hi = res["intervals"]["interface.traction.stiffness"]
    assert lo < 2e13 * 1.05 and hi > 2e13 * 0.95
    # a waveform the forward run does not have is a ValueError naming the field
    spec["records"]["waveform"] = "echo"
    with pytest.raises(ValueError, match="records.waveform"):
        cw.identify(spec)
