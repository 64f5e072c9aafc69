"""2D runs from Python (`cw.run` on a `solid_2d` scenario): numpy arrays of the receivers
and the crack's fields, the energy audit, Signorini in the crack's records."""

import numpy as np
import pytest

import contactwave as cw

SMALL = {
    "model": {"kind": "solid_2d", "width": 2e-3, "duration": 0.6e-6, "element_size": 0.1e-3},
    "layer": [{"thickness": 1e-3, "material": "aluminium"}],
    "crack": [
        {
            "start": [0.7e-3, 0.5e-3],
            "end": [1.3e-3, 0.5e-3],
            "static_pressure": 0.2e6,
            "tangential": {"law": "coulomb", "friction": 0.3},
        }
    ],
    "source": [
        {
            "x0": 0.6e-3,
            "x1": 1.4e-3,
            "signal": {"frequency": 10e6, "cycles": 2, "amplitude": 10e6, "window": "hann"},
        }
    ],
    "receiver": [{"name": "top", "at": [1e-3, 0.0]}, {"name": "under", "at": [1e-3, 1e-3]}],
}


def test_a_clapping_crack_in_2d_gives_numpy_arrays():
    r = cw.run(SMALL)
    assert isinstance(r, cw.Solid2dResult)
    n = len(r.t)
    # one row per receiver and component (n_receivers, n_t), in receivers.csv's order
    assert r.receivers.shape == (4, n) and r.receivers.dtype == np.float64
    assert r.components == ["x", "z"]
    assert r.receiver_names == ["top", "top", "under", "under"]
    assert r.receiver_components == ["x", "z", "x", "z"]
    assert np.array_equal(r.velocity("under", "z"), r.receivers[3])
    assert np.array_equal(r.velocity("top", "x"), r.receivers[0])
    # with their coordinates: the receivers' positions, the crack nodes' x and z
    assert np.allclose(r.receiver_x, [1e-3] * 4)
    assert np.allclose(r.receiver_z, [0.0, 0.0, 1e-3, 1e-3])
    assert r.stress_x.shape == (0,) and r.stress_z.shape == (0,)
    # an unknown receiver or component names the valid ones
    for name, comp, valid in (("nope", "z", "top, under"), ("top", "y", "x, z")):
        try:
            r.velocity(name, comp)
        except ValueError as e:
            assert valid in str(e), e
        else:
            raise AssertionError("no error")
    assert repr(r).startswith("Solid2dResult(scenario=")
    # no stress receivers in this file: an empty array of the right shape
    assert r.stresses.shape == (0, n) and r.stress_components == []
    assert r.summary["energy_closure_error"] < 1e-9
    # the crack's energy audit: friction dissipates part of the shear tractions' work (the
    # rest: the tangential arrest of the faces at each closure, rigid stick storing nothing;
    # measured 0.95 of it here), no damage law, no static shear
    s = r.summary
    assert s["energy_damage"] == 0.0 and s["energy_static_shear_work"] == 0.0
    assert 0.0 < s["energy_friction"] <= 1.001 * s["energy_cracks_tangential"]
    assert s["energy_cracks_tangential"] <= s["energy_cracks"]
    c = r.cracks[0]
    nodes, records = c["normal_gap"].shape
    assert nodes == len(c["position"]) and records == len(c["time"])
    assert np.allclose(c["x"], 0.7e-3 + c["position"]) and np.allclose(c["z"], 0.5e-3)
    assert 0.7e-3 < np.min(c["x"]) and np.max(c["x"]) < 1.3e-3
    gap, stress = c["normal_gap"], c["normal_stress"]
    # the crack opens, never interpenetrates, and carries no stress while open
    assert gap.max() > 0.0 and gap.min() >= 0.0
    assert np.all((gap == 0.0) | (np.abs(stress) < 1e-3))
    # the contact state: open (0) exactly where the gap is
    assert c["state"].shape == gap.shape
    assert np.array_equal(c["state"] == 0.0, gap > 0.0)


def test_stress_receivers_come_one_row_per_component():
    d = {**SMALL, "receiver": SMALL["receiver"] + [
        {"name": "s", "at": [0.5e-3, 0.25e-3], "quantity": "stress"}]}
    r = cw.run(d)
    n = len(r.t)
    assert r.stresses.shape == (3, n)
    assert r.stress_names == ["s", "s", "s"] and r.stress_components == ["xx", "zz", "xz"]
    assert np.allclose(r.stress_x, 0.5e-3) and np.allclose(r.stress_z, 0.25e-3)
    assert np.array_equal(r.stress("s", "zz"), r.stresses[1])
    # the burst reaches the point: a dynamic stress, and the velocity receivers unchanged
    assert np.abs(r.stress("s", "zz")).max() > 1e4
    assert np.array_equal(cw.run(SMALL).receivers, r.receivers)


def test_snapshots_come_as_an_image_stack_with_coordinates():
    d = {**SMALL, "snapshots": {"times": [0.3e-6, 0.6e-6], "pixels": 40, "field": "vz"}}
    r = cw.run(d)
    # 40 px across 2 mm: 20 rows of 50 um; the pixel centres
    assert r.snapshots.shape == (2, 20, 40) and r.snapshots.dtype == np.float64
    assert np.allclose(r.snapshot_x, (np.arange(40) + 0.5) * 50e-6)
    assert np.allclose(r.snapshot_z, (np.arange(20) + 0.5) * 50e-6)
    assert r.snapshot_field == "vz"
    assert np.all(np.abs(r.snapshot_times - [0.3e-6, 0.6e-6]) <= r.dt / 2 + 1e-18)
    # the burst has reached the plate by then: the field moves, and snapshots change no
    # other output
    assert np.abs(r.snapshots).max() > 0.0
    plain = cw.run(SMALL)
    assert np.array_equal(plain.receivers, r.receivers)
    assert plain.snapshots.shape == (0, 0, 0)


def test_sweep_keys_may_leave_out_the_only_index_and_name_friction_mu(root):
    """`source.angle` is `source.0.angle` and `crack.tangential.mu` is
    `crack.0.tangential.friction` when the scenario has one source and one crack."""
    base = str(root / "examples" / "solid_2d" / "plate_crack_quick.toml")
    short = cw.sweep(
        base, {"source.angle": [0.0, 20.0], "crack.tangential.mu": [0.1]}, as_frame=False
    )
    full = cw.sweep(
        base,
        {"source.0.angle": [0.0, 20.0], "crack.0.tangential.friction": [0.1]},
        as_frame=False,
    )
    a, b = short["bottom_A2_over_A1"], full["bottom_A2_over_A1"]
    assert np.array_equal(a, b)
    assert np.all(np.isfinite(a)) and a[0] != a[1]


def test_one_value_swept_under_two_spellings_is_refused(root):
    """An index-free key and its index 0 (or `mu` and `friction`) set one value: two axes
    on it would label each row with a value the run did not take."""
    base = str(root / "examples" / "solid_2d" / "plate_crack_quick.toml")
    for axes in (
        {"source.angle": [0.0], "source.0.angle": [15.0]},
        {"crack.0.length": [1e-3], "crack.length": [2e-3]},
        {"crack.tangential.mu": [0.1], "crack.0.tangential.friction": [0.2]},
    ):
        with pytest.raises(ValueError, match="swept by an earlier axis already"):
            cw.sweep(base, axes, as_frame=False)


def test_a_sweep_base_may_be_given_as_toml_text(root):
    path = root / "examples" / "solid_2d" / "plate_crack_quick.toml"
    axes = {"crack.0.length": [1e-3, 2e-3]}
    by_text = cw.sweep(path.read_text(), axes, as_frame=False)
    by_path = cw.sweep(str(path), axes, as_frame=False)
    assert np.array_equal(by_text["bottom_A2_over_A1"], by_path["bottom_A2_over_A1"])
    assert cw.memory_estimate(path.read_text(), axes).shape == (2,)


def test_a_scenario_may_be_given_as_toml_text(root):
    path = root / "examples" / "solid_2d" / "plate_crack_quick.toml"
    text = path.read_text()
    assert cw.scenario_from_toml(text, file="quick.toml").kind == "solid_2d"
    # a string with a line break is the scenario's text, not a file name
    assert cw._as_scenario(text).kind == "solid_2d"
    with pytest.raises(ValueError, match=r"^bad\.toml: line 2"):
        cw.scenario_from_toml("[model]\nkind = \n", file="bad.toml")


def test_a_gmsh_mesh_run_gives_arrays_with_the_cracks_coordinates():
    # the reference plate rotated by 30 degrees, meshed by Gmsh (examples/solid_2d/mesh/):
    # the crack's points carry their own coordinates, on the rotated crack line
    from pathlib import Path

    root = Path(__file__).resolve().parents[2]
    msh = root / "examples" / "solid_2d" / "mesh" / "rotated" / "plate_30.msh"
    s, c = np.sin(np.radians(30.0)), np.cos(np.radians(30.0))
    rot = lambda x, z: [c * x - s * z, s * x + c * z]  # noqa: E731
    scenario = {
        "model": {"kind": "solid_2d", "duration": 3e-6, "harmonic": 2},
        "mesh": {"file": str(msh), "order": 4},
        "material": [{"group": "aluminium", "material": "aluminium"}],
        "crack": [{"group": "crack", "static_pressure": 0.2e6}],
        "source": [
            {
                "kind": "transducer",
                "group": "wedge",
                "signal": {"frequency": 2e6, "cycles": 3, "amplitude": 10e6, "window": "hann"},
            }
        ],
        "receiver": [{"name": "far", "at": rot(30e-3, 0.0)}],
    }
    r = cw.run(scenario)
    assert r.receivers.shape[0] == 2
    assert np.allclose([r.receiver_x[0], r.receiver_z[0]], rot(30e-3, 0.0))
    assert r.summary["energy_closure_error"] < 1e-9
    crack = r.cracks[0]
    x, z = np.asarray(crack["x"]), np.asarray(crack["z"])
    # back in the plate's frame: the crack from x = 19 to 21 mm at z = 5 mm
    xp, zp = c * x + s * z, -s * x + c * z
    assert np.allclose(zp, 5e-3, atol=1e-9)
    assert xp.min() > 19e-3 - 1e-9 and xp.max() < 21e-3 + 1e-9
    assert np.allclose(crack["position"], xp - xp.min(), atol=1e-9)


# (the run is cut to 2 us, shorter than the burst: the warning that says so is expected)
@pytest.mark.filterwarnings("ignore:.*shorter than source")
def test_snapshots_on_a_mesh_are_nan_in_the_hole_and_finite_in_the_plate(root):
    # the rivet plate (Gmsh, second order): a 60 x 30 mm strip with a 3 mm hole at
    # (30, 15) mm; the pixels whose centres lie in the hole have no value (NaN), the
    # others carry the field
    path = root / "examples" / "solid_2d" / "mesh" / "rivet_hole" / "rivet_hole.toml"
    text = path.read_text().replace("duration = 16e-6", "duration = 2e-6")
    r = cw.run(cw.scenario_from_toml(text, str(path)))
    assert r.snapshots.ndim == 3 and r.snapshots.shape[0] >= 1
    x, z = np.meshgrid(r.snapshot_x, r.snapshot_z)
    d = np.hypot(x - 30e-3, z - 15e-3)
    frame = r.snapshots[-1]
    assert np.all(np.isnan(frame[d < 2.9e-3]))
    # (away from the rim, where a pixel may straddle it; the crack runs from 33 to 35 mm)
    assert np.all(np.isfinite(frame[d > 3.1e-3]))
    assert np.nanmax(np.abs(frame)) > 0.0
