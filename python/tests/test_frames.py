"""Result.to_pandas() / to_xarray() (issue 27 item 2, issue 28 item 3) and the HDF5 result
files opened from Python with h5py (`contactwave run --hdf5`, `sweep --hdf5`), with their
units and provenance attributes."""

import hashlib
import subprocess
import sys

import numpy as np
import pytest

import contactwave as cw
from conftest import CHEAP
from test_solid_2d import SMALL

pd = pytest.importorskip("pandas")
xr = pytest.importorskip("xarray")
h5py = pytest.importorskip("h5py")

pytestmark = pytest.mark.filterwarnings("ignore::contactwave.HarmonicFloorWarning")


def test_half_space_to_pandas_and_xarray_carry_the_arrays_and_units():
    r = cw.run(CHEAP)
    df = r.to_pandas()
    assert df.index.name == "t" and np.array_equal(df.index.to_numpy(), r.t)
    assert np.array_equal(df["gap"].to_numpy(), r.gap)
    assert df.attrs["units"]["contact_stress"] == "Pa" and df.attrs["units"]["t"] == "s"
    probe = r.to_pandas("probe")
    assert np.array_equal(probe["reflected_velocity"].to_numpy(), r.probe_reflected_velocity)
    assert probe.attrs["units"]["reflected_velocity"] == "m/s"
    spec = r.to_pandas("spectrum")
    assert spec.index.name == "frequency"
    with pytest.raises(ValueError, match="timeseries"):
        r.to_pandas("nope")
    ds = r.to_xarray()
    assert ds["gap"].dims == ("time",) and ds["gap"].attrs["units"] == "m"
    assert ds["time"].attrs["units"] == "s" and ds["frequency"].attrs["units"] == "Hz"
    assert np.array_equal(ds["reflected_stress"].to_numpy(), r.reflected_stress)
    assert ds.attrs["A2_over_Ainc"] == r.summary["A2_over_Ainc"]


def test_solid_2d_to_xarray_has_time_x_z_coordinates_with_units():
    d = {**SMALL, "snapshots": {"times": [0.3e-6, 0.6e-6], "pixels": 40, "field": "vz"}}
    r = cw.run(d)
    ds = r.to_xarray()
    assert ds["velocity"].dims == ("receiver", "component", "time")
    assert ds["velocity"].attrs["units"] == "m/s"
    assert np.array_equal(ds["velocity"].sel(receiver="under", component="z").to_numpy(),
                          r.velocity("under", "z"))
    assert ds["snapshot"].dims == ("snapshot_time", "z", "x")
    for c, u in (("time", "s"), ("x", "m"), ("z", "m"), ("snapshot_time", "s")):
        assert ds[c].attrs["units"] == u
    assert ds["crack0_normal_gap"].attrs["units"] == "m"
    df = r.to_pandas()
    assert list(df.columns) == ["top_vx", "top_vz", "under_vx", "under_vz"]
    assert df.attrs["units"]["top_vz"] == "m/s"


def test_a_missing_extra_is_an_import_error_naming_it(monkeypatch):
    r = cw.run(CHEAP)
    monkeypatch.setitem(sys.modules, "xarray", None)
    with pytest.raises(ImportError, match=r"contactwave\[xarray\]"):
        r.to_xarray()
    monkeypatch.setitem(sys.modules, "pandas", None)
    with pytest.raises(ImportError, match=r"contactwave\[pandas\]"):
        r.to_pandas()


def _sha256(path):
    return hashlib.sha256(path.read_bytes()).hexdigest()


def test_result_h5_opens_in_h5py_with_units_and_provenance(cli, root, tmp_path):
    scenario = root / "examples" / "rccm_0.82MPa.toml"
    out = tmp_path / "run"
    subprocess.run([str(cli), "run", str(scenario), "--out", str(out), "--hdf5"],
                   check=True, capture_output=True)
    with h5py.File(out / "result.h5", "r") as f:
        assert f.attrs["scenario_sha256"] == _sha256(scenario)
        assert f.attrs["contactwave_version"] == cw.__version__
        assert f["timeseries/gap"].attrs["units"] == "m"
        assert f["timeseries/t"].attrs["units"] == "s"
        gap = f["timeseries/gap"][()]
        assert gap.dtype == np.float64
        csv = pd.read_csv(out / "timeseries.csv")
        assert np.array_equal(gap, csv["gap"].to_numpy())
        assert f["spectrum/frequency"].attrs["units"] == "Hz"
    # xarray opens a group of it too (h5netcdf or netCDF4 engines where installed)
    summary = (out / "summary.json").read_text()
    assert '"provenance"' in summary and '"scenario_sha256"' in summary


def test_sweep_h5_and_the_sidecar_open_from_python(cli, root, tmp_path):
    sweep = root / "examples" / "unilateral_xi_sweep.toml"
    out = tmp_path / "sweep"
    subprocess.run([str(cli), "sweep", str(sweep), "--out", str(out), "--hdf5",
                    "--threads", "2"], check=True, capture_output=True)
    table = pd.read_csv(out / "sweep.csv")  # still a plain table
    with h5py.File(out / "sweep.h5", "r") as f:
        assert set(f["sweep"].keys()) == set(table.columns)
        assert np.array_equal(f["sweep/point"][()], table["point"].to_numpy())
        assert f.attrs["scenario_sha256"] == _sha256(sweep)
    import json
    p = json.loads((out / "provenance.json").read_text())["provenance"]
    assert p["scenario_sha256"] == _sha256(sweep)


def test_bar_stack_to_pandas_and_xarray(root):
    r = cw.run(root / "examples" / "bar_stack_incident.toml")
    df = r.to_pandas()
    n = r.gap.shape[0]
    assert list(df.columns[:3]) == ["force", "displacement", "acceleration"]
    assert [f"gap_{i}" for i in range(n)] == [c for c in df.columns if c.startswith("gap_")]
    assert np.array_equal(df["pressure_0"].to_numpy(), r.pressure[0])
    assert df.attrs["units"]["pressure_0"] == "Pa" and df.attrs["units"]["t"] == "s"
    ds = r.to_xarray()
    assert ds["gap"].dims == ("interface", "time") and ds["gap"].attrs["units"] == "m"
    assert ds.sizes["interface"] == n and ds["time"].attrs["units"] == "s"
    assert np.array_equal(ds["stiffness"].to_numpy(), r.stiffness)


def test_solid_2d_to_xarray_leaves_out_what_the_run_does_not_have():
    # issue 56 item 10: no empty dimensions or variables (no [snapshots], no stress
    # receivers, no velocity receivers)
    def empty(ds):
        return sorted([d for d, n in ds.sizes.items() if n == 0]
                      + [k for k, v in ds.variables.items() if v.size == 0])

    ds = cw.run(SMALL).to_xarray()
    assert empty(ds) == []
    assert "velocity" in ds and "crack0_state" in ds
    for name in ("stress", "snapshot", "stress_receiver", "snapshot_time", "x", "z"):
        assert name not in ds.variables and name not in ds.sizes, name
    stress = {"name": "s", "at": [0.5e-3, 0.25e-3], "quantity": "stress"}
    r = cw.run({**SMALL, "receiver": [stress]})
    ds = r.to_xarray()
    assert empty(ds) == []
    assert "velocity" not in ds and "receiver" not in ds.sizes
    assert np.array_equal(ds["stress"].sel(stress_receiver="s", stress_component="zz")
                          .to_numpy(), r.stress("s", "zz"))
    # with snapshots the frames are there, on their coordinates
    d = {**SMALL, "snapshots": {"times": [0.3e-6], "pixels": 40}}
    ds = cw.run(d).to_xarray()
    assert empty(ds) == [] and ds["snapshot"].shape == (1, 20, 40)
