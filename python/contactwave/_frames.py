"""``to_pandas()`` / ``to_xarray()`` of the result objects (docs/python.md).

pandas and xarray are optional (the ``pandas`` and ``xarray`` extras); a missing one raises
``ImportError`` naming the extra. Units (SI) are attributes: ``DataFrame.attrs["units"]``
maps each column to its unit; every xarray variable and coordinate has ``attrs["units"]``.
"""

from __future__ import annotations

import importlib
from typing import Any, Dict, Mapping

import numpy as np


def unique(names: Any) -> list:
    """``names`` without repeats, in their first order (a 2D result's per-row labels)."""
    return list(dict.fromkeys(names))

#: Units of the columns of the half-space result (timeseries, probe, spectrum).
HALF_SPACE_UNITS: Dict[str, str] = {
    "t": "s",
    "gap": "m",
    "contact_stress": "Pa",
    "beta": "1",
    "incident_stress": "Pa",
    "reflected_stress": "Pa",
    "transmitted_stress": "Pa",
    "probe_t": "s",
    "probe_incident_stress": "Pa",
    "probe_reflected_stress": "Pa",
    "probe_incident_velocity": "m/s",
    "probe_reflected_velocity": "m/s",
    "probe_displacement": "m",
    "frequency": "Hz",
    "incident": "m",
    "reflected": "m",
}

#: Units of the bar-stack arrays.
BAR_STACK_UNITS: Dict[str, str] = {
    "t": "s",
    "force": "N",
    "displacement": "m",
    "acceleration": "m/s^2",
    "gap": "m",
    "pressure": "Pa",
    "beta": "1",
    "stiffness": "Pa/m",
}


def require(module: str, extra: str, what: str) -> Any:
    """Import ``module`` or raise ImportError naming the ``extra`` that installs it."""
    try:
        return importlib.import_module(module)
    except ImportError as e:
        raise ImportError(
            f"{what} needs {module}, which `pip install contactwave` does not install: "
            f'pip install "contactwave[{extra}]" (or `pip install ".[{extra}]"` in the '
            "repository)"
        ) from e


def _numbers(summary: Mapping[str, Any]) -> Dict[str, Any]:
    """The summary's numbers (attributes of a Dataset)."""
    return {k: v for k, v in summary.items() if isinstance(v, (int, float)) and k != "provenance"}


def half_space_pandas(r: Any, table: str) -> Any:
    pd = require("pandas", "pandas", "Result.to_pandas()")
    if table == "timeseries":
        cols = ["gap", "contact_stress", "beta", "incident_stress", "reflected_stress",
                "transmitted_stress"]
        df = pd.DataFrame({c: getattr(r, c) for c in cols},
                          index=pd.Index(r.t, name="t"))
    elif table == "probe":
        cols = ["probe_incident_stress", "probe_reflected_stress", "probe_incident_velocity",
                "probe_reflected_velocity", "probe_displacement"]
        df = pd.DataFrame({c[len("probe_"):]: getattr(r, c) for c in cols},
                          index=pd.Index(r.probe_t, name="t"))
        df.attrs["probe_x"] = r.probe_x
        units = {c[len("probe_"):]: HALF_SPACE_UNITS[c] for c in cols}
        units["t"] = "s"
        df.attrs["units"] = units
        return df
    elif table == "spectrum":
        s = r.spectrum()
        df = pd.DataFrame({"incident": s.incident, "reflected": s.reflected},
                          index=pd.Index(s.frequency, name="frequency"))
    elif table == "shear":
        if r.shear is None:
            raise ValueError("this run has no tangential part (Result.shear is None)")
        n = len(r.t)
        cols = {k: v for k, v in r.shear.items() if np.ndim(v) == 1 and len(v) == n}
        df = pd.DataFrame(cols, index=pd.Index(r.t, name="t"))
        df.attrs["units"] = {k: ("m" if "gap" in k or k == "slip" else
                                 "1" if k == "slip_state" else "Pa") for k in cols}
        df.attrs["units"]["t"] = "s"
        return df
    else:
        raise ValueError(
            f"table {table!r}: one of 'timeseries', 'probe', 'spectrum', 'shear'")
    df.attrs["units"] = {c: HALF_SPACE_UNITS.get(c, "") for c in [df.index.name, *df.columns]}
    return df


def half_space_xarray(r: Any) -> Any:
    xr = require("xarray", "xarray", "Result.to_xarray()")
    s = r.spectrum()
    u = HALF_SPACE_UNITS
    data = {}
    for c in ["gap", "contact_stress", "beta", "incident_stress", "reflected_stress",
              "transmitted_stress"]:
        data[c] = ("time", getattr(r, c), {"units": u[c]})
    for c in ["probe_incident_stress", "probe_reflected_stress", "probe_incident_velocity",
              "probe_reflected_velocity", "probe_displacement"]:
        data[c] = ("probe_time", getattr(r, c), {"units": u[c]})
    data["incident_spectrum"] = ("frequency", s.incident, {"units": "m"})
    data["reflected_spectrum"] = ("frequency", s.reflected, {"units": "m"})
    coords = {
        "time": ("time", r.t, {"units": "s"}),
        "probe_time": ("probe_time", r.probe_t, {"units": "s"}),
        "frequency": ("frequency", s.frequency, {"units": "Hz"}),
    }
    ds = xr.Dataset(data, coords=coords, attrs=_numbers(r.summary))
    ds.attrs["probe_x"] = r.probe_x
    return ds


def bar_stack_pandas(r: Any) -> Any:
    pd = require("pandas", "pandas", "BarStackResult.to_pandas()")
    cols: Dict[str, np.ndarray] = {
        "force": r.force, "displacement": r.displacement, "acceleration": r.acceleration,
    }
    units = {"t": "s", "force": "N", "displacement": "m", "acceleration": "m/s^2"}
    for name in ("gap", "pressure", "beta", "stiffness"):
        a = np.asarray(getattr(r, name))
        for i in range(a.shape[0]):
            cols[f"{name}_{i}"] = a[i]
            units[f"{name}_{i}"] = BAR_STACK_UNITS[name]
    df = pd.DataFrame(cols, index=pd.Index(r.t, name="t"))
    df.attrs["units"] = units
    return df


def bar_stack_xarray(r: Any) -> Any:
    xr = require("xarray", "xarray", "BarStackResult.to_xarray()")
    u = BAR_STACK_UNITS
    data = {k: ("time", getattr(r, k), {"units": u[k]})
            for k in ("force", "displacement", "acceleration")}
    coords = {"time": ("time", r.t, {"units": "s"})}
    n = np.asarray(r.gap).shape[0]
    if n:  # (a stack without interfaces has no interface dimension, not an empty one)
        for k in ("gap", "pressure", "beta", "stiffness"):
            data[k] = (("interface", "time"), np.asarray(getattr(r, k)), {"units": u[k]})
        coords["interface"] = ("interface", np.arange(n), {"units": "1"})
    return xr.Dataset(data, coords=coords, attrs=_numbers(r.summary))


def solid_2d_pandas(r: Any) -> Any:
    pd = require("pandas", "pandas", "Solid2dResult.to_pandas()")
    cols: Dict[str, np.ndarray] = {}
    units = {"t": "s"}
    for row, name, c in zip(r.receivers, r.receiver_names, r.receiver_components):
        cols[f"{name}_v{c}"] = row
        units[f"{name}_v{c}"] = "m/s"
    for row, name, c in zip(r.stresses, r.stress_names, r.stress_components):
        cols[f"{name}_s{c}"] = row
        units[f"{name}_s{c}"] = "Pa"
    df = pd.DataFrame(cols, index=pd.Index(r.t, name="t"))
    df.attrs["units"] = units
    return df


def solid_2d_xarray(r: Any) -> Any:
    xr = require("xarray", "xarray", "Solid2dResult.to_xarray()")
    # the rows (one per point and component, point-major) as point x component x time;
    # a part the run does not have (no velocity or stress receivers, no [snapshots], a
    # crack without records) is left out with its dimensions, not given as empty ones
    nt = len(r.t)
    data: Dict[str, Any] = {}
    coords: Dict[str, Any] = {"time": ("time", r.t, {"units": "s"})}
    points = unique(r.receiver_names)
    if points:
        comps = list(r.components)
        data["velocity"] = (("receiver", "component", "time"),
                            r.receivers.reshape(len(points), len(comps), nt), {"units": "m/s"})
        # labels: no unit (CF's "1" for a dimensionless quantity would mislead)
        coords["receiver"] = ("receiver", points, {"units": "", "long_name": "receiver name"})
        coords["component"] = ("component", comps,
                               {"units": "", "long_name": "velocity component (axis)"})
    spoints = unique(r.stress_names)
    if spoints:
        scomps = unique(r.stress_components)
        data["stress"] = (("stress_receiver", "stress_component", "time"),
                          r.stresses.reshape(len(spoints), len(scomps), nt), {"units": "Pa"})
        coords["stress_receiver"] = ("stress_receiver", spoints,
                                     {"units": "", "long_name": "stress receiver name"})
        coords["stress_component"] = ("stress_component", scomps,
                                      {"units": "", "long_name": "stress component (axes)"})
    if len(r.snapshot_times):
        data["snapshot"] = (("snapshot_time", "z", "x"), r.snapshots,
                            {"units": "m/s", "field": r.snapshot_field})
        coords["snapshot_time"] = ("snapshot_time", r.snapshot_times, {"units": "s"})
        coords["z"] = ("z", r.snapshot_z, {"units": "m"})
        coords["x"] = ("x", r.snapshot_x, {"units": "m"})
    for k, c in enumerate(r.cracks):
        if not (len(c["position"]) and len(c["time"])):
            continue
        p = f"crack{k}_"
        coords[p + "position"] = (p + "position", c["position"], {"units": "m"})
        coords[p + "time"] = (p + "time", c["time"], {"units": "s"})
        for field, unit in (("normal_gap", "m"), ("tangential_gap", "m"),
                            ("normal_stress", "Pa"), ("shear_stress", "Pa"),
                            ("adhesion", "1"), ("state", "1")):
            if field in c:
                data[p + field] = ((p + "position", p + "time"), c[field], {"units": unit})
    return xr.Dataset(data, coords=coords, attrs=_numbers(r.summary))
