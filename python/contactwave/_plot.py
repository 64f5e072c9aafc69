"""``.plot()`` of the result objects and :func:`contactwave.plot_sweep` (docs/python.md).

matplotlib is optional (the ``plot`` extra) and imported only when a plot is drawn; a
missing matplotlib raises ``ImportError`` naming the extra. Every helper draws one panel
into ``ax`` (a new figure when ``None``) and returns that Axes. The lines hold the result's
own arrays in SI units (s, Hz, m/s, Pa, ...); the tick labels carry SI prefixes with the
unit (``matplotlib.ticker.EngFormatter``: ``5 µs`` on an axis labelled ``time t (s)``,
``300 mm/s`` on one in m/s). A spectrum's log axis spans its bins above 0 Hz (the DC bin,
near zero once the mean is removed, would stretch it over decades of nothing) and its
harmonic markers sit at n f0 of the scenario's fundamental in Hz (a unit string such as
``"1 MHz"`` read as the library reads it).
"""

from __future__ import annotations

import json
import math
import warnings
from typing import Any, Dict, List, Mapping, Optional, Sequence

import numpy as np

from . import _core
from ._frames import require, unique

#: Harmonics marked on the spectra: n f0 for n = 1 ... HARMONICS.
HARMONICS = 5


def _axes(ax: Any, what: str) -> Any:
    """``ax``, or the Axes of a new figure; ImportError naming the extra without
    matplotlib."""
    plt = require("matplotlib.pyplot", "plot", what)
    if ax is None:
        _fig, ax = plt.subplots()
    return ax


def _eng(axis: Any, unit: str) -> None:
    """SI prefixes and the ``unit`` on the tick labels of ``axis`` (``ax.xaxis`` /
    ``ax.yaxis``): ``300 mm/s``, ``5 µs``, ``2 MHz`` (a prefix alone, ``300 m`` on an axis
    in m/s, reads as metres)."""
    from matplotlib.ticker import EngFormatter

    axis.set_major_formatter(EngFormatter(unit=unit, sep=" "))


def _log_limits(ax: Any, frequency: Any, *magnitudes: Any) -> None:
    """The log y axis of a spectrum over the positive values of its bins above 0 Hz (the
    DC bin left out: after the mean is removed it holds rounding, decades below the
    rest), with a tenth of a decade of room."""
    f = np.asarray(frequency, dtype=np.float64)
    keep = f > 0
    values = np.concatenate([np.asarray(m, dtype=np.float64)[keep] for m in magnitudes])
    values = values[np.isfinite(values) & (values > 0)]
    if values.size:
        lo, hi = float(values.min()), float(values.max())
        ax.set_ylim(lo / 10**0.1, hi * 10**0.1)


def label(key: str) -> str:
    """Axis label of a dotted scenario key or a summary key: ``name (unit)``, as the
    CLI's plots name them (``interface.static_pressure`` -> ``static pressure p0 (Pa)``)."""
    name, unit = _core.quantity(key)
    return f"{name} ({unit})" if unit else name


def _tag(keys: Sequence[str], values: Sequence[float]) -> str:
    """``static pressure p0 = 1e+05 Pa, ...``: the values of further conditions or axes."""
    parts = []
    for k, v in zip(keys, values):
        name, unit = _core.quantity(k)
        parts.append(f"{name} = {v:.4g} {unit}".rstrip())
    return ", ".join(parts)


def _harmonic_markers(ax: Any, f0: float) -> None:
    """Dotted vertical lines at n f0 (n = 1 ... HARMONICS), each labelled ``n f0`` at the
    top of the panel; their ``gid`` is ``harmonic_n``."""
    if not (math.isfinite(f0) and f0 > 0):
        return
    for n in range(1, HARMONICS + 1):
        line = ax.axvline(n * f0, color="0.5", linestyle=":", linewidth=1.0)
        line.set_gid(f"harmonic_{n}")
        ax.annotate(
            "f0" if n == 1 else f"{n}f0",
            xy=(n * f0, 1.0),
            xycoords=("data", "axes fraction"),
            xytext=(2, -10),
            textcoords="offset points",
            fontsize=8,
            color="0.35",
        )


def _hz(key: str, value: Any) -> float:
    """A frequency of a scenario's table in Hz: a number, or a unit string (``"1 MHz"``)
    converted as the library converts it; NaN for anything else."""
    if isinstance(value, bool):
        return math.nan
    if isinstance(value, (int, float)):
        return float(value)
    if isinstance(value, str):
        try:
            return float(_core.si_value(key, value))
        except ValueError:
            return math.nan
    return math.nan


def _scenario_f0(scenario: Any) -> float:
    """The fundamental (Hz) of a scenario: ``incident.frequency`` (half space),
    ``source.0.signal.frequency`` (2D), numbers or unit strings; NaN when it has none."""
    try:
        table = json.loads(scenario.to_json())
    except Exception:  # noqa: BLE001 - a result without its scenario: no markers
        return math.nan
    incident = table.get("incident", {})
    if isinstance(incident, Mapping) and "frequency" in incident:
        return _hz("incident.frequency", incident["frequency"])
    # 2D: the first source's signal
    sources = table.get("source", [])
    if isinstance(sources, list) and sources and isinstance(sources[0], Mapping):
        signal = sources[0].get("signal", {})
        if isinstance(signal, Mapping) and "frequency" in signal:
            return _hz("source.0.signal.frequency", signal["frequency"])
    return math.nan


# ---------------------------------------------------------------------------------------
# Half space
# ---------------------------------------------------------------------------------------

_HALF_SPACE_KINDS = ("signals", "probe", "gap", "spectrum")


def half_space(r: Any, kind: str, ax: Any) -> Any:
    if kind not in _HALF_SPACE_KINDS:
        raise ValueError(f"kind {kind!r}: one of {', '.join(map(repr, _HALF_SPACE_KINDS))}")
    ax = _axes(ax, "Result.plot()")
    if kind == "signals":
        for name, y in (
            ("incident", r.incident_stress),
            ("reflected", r.reflected_stress),
            ("transmitted", r.transmitted_stress),
        ):
            ax.plot(r.t, y, label=name, linewidth=1.0)
        ax.set_ylabel("stress at the interface (Pa)")
        ax.set_title("interface stresses (tension positive)")
        _eng(ax.yaxis, "Pa")
    elif kind == "probe":
        ax.plot(r.probe_t, r.probe_incident_velocity, label="incident", linewidth=1.0)
        ax.plot(r.probe_t, r.probe_reflected_velocity, label="reflected", linewidth=1.0)
        ax.set_ylabel("particle velocity (m/s)")
        ax.set_title(f"probe at x = {r.probe_x:.4g} m")
        _eng(ax.yaxis, "m/s")
    elif kind == "gap":
        ax.plot(r.t, r.gap, label="gap", linewidth=1.0)
        ax.set_ylabel("gap [u] (m)")
        ax.set_title("interface gap (opening positive)")
        _eng(ax.yaxis, "m")
    else:
        s = r.spectrum()
        ax.semilogy(s.frequency, s.incident, label="incident", linewidth=1.0)
        ax.semilogy(s.frequency, s.reflected, label="reflected", linewidth=1.0)
        _log_limits(ax, s.frequency, s.incident, s.reflected)
        _harmonic_markers(ax, _scenario_f0(r.scenario))
        ax.set_xlabel("frequency f (Hz)")
        ax.set_ylabel("velocity spectrum |V(f)| (m/s s)")
        ax.set_title(f"spectra ({r.analysis_method}: A2/A1 = {r.summary.get('A2_over_A1', math.nan):.4g})")
        _eng(ax.xaxis, "Hz")
        ax.legend()
        return ax
    ax.set_xlabel("time t (s)")
    _eng(ax.xaxis, "s")
    ax.legend()
    return ax


# ---------------------------------------------------------------------------------------
# Finite cracks in 2D
# ---------------------------------------------------------------------------------------


def _pick(names: Sequence[str], chosen: Any, what: str) -> List[str]:
    if chosen is None:
        return list(names)
    chosen = [chosen] if isinstance(chosen, str) else list(chosen)
    for c in chosen:
        if c not in names:
            raise ValueError(f"{what} {c!r}: one of {', '.join(map(repr, names))}")
    return chosen


def _records_2d(r: Any, receivers: Any, component: Any) -> Any:
    """The records a 2D plot draws: velocity receivers (the default where the run has
    any) or stress receivers (where it has only those, or where ``receivers`` names only
    stress receivers), as ``(names, components, record(name, c), quantity, unit, symbol)``."""
    velocity, stress = unique(r.receiver_names), unique(r.stress_names)
    chosen = [receivers] if isinstance(receivers, str) else receivers
    use_stress = (not velocity and bool(stress)) or (
        chosen is not None and bool(list(chosen)) and all(c in stress for c in chosen)
    )
    if use_stress:
        names = _pick(stress, receivers, "stress receiver")
        comps = _pick(unique(r.stress_components), component, "stress component")
        return names, comps, r.stress, "stress", "Pa", "s"
    if not velocity:
        raise ValueError("the run has no receivers to plot (add a [[receiver]] table)")
    if chosen is not None:
        mixed = [c for c in chosen if c in stress and c not in velocity]
        if mixed:
            raise ValueError(
                f"receiver {mixed[0]!r} records stress (Pa): a plot draws velocity "
                f"receivers or stress receivers, not both; velocity receivers: "
                f"{', '.join(map(repr, velocity))}")
    names = _pick(velocity, receivers, "receiver")
    comps = _pick(r.components, component, "component")
    return names, comps, r.velocity, "particle velocity", "m/s", "v"


def solid_2d(r: Any, kind: str, ax: Any, receivers: Any, component: Any) -> Any:
    kinds = ("receivers", "spectrum")
    if kind not in kinds:
        raise ValueError(f"kind {kind!r}: one of {', '.join(map(repr, kinds))}")
    names, comps, record, quantity, unit, symbol = _records_2d(r, receivers, component)
    ax = _axes(ax, "Solid2dResult.plot()")
    if kind == "receivers":
        for name in names:
            for c in comps:
                ax.plot(r.t, record(name, c), label=f"{name} {symbol}{c}", linewidth=1.0)
        ax.set_xlabel("time t (s)")
        ax.set_ylabel(f"{quantity} ({unit})")
        ax.set_title("receivers")
        _eng(ax.xaxis, "s")
        _eng(ax.yaxis, unit)
        ax.legend()
        return ax
    # the library's spectrum of each record (the analysis of `contactwave analyze`)
    f0 = _scenario_f0(getattr(r, "scenario", None))
    from .measured import analyze

    spectra = []
    for name in names:
        for c in comps:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                a = analyze(record(name, c), dt=float(r.t[1] - r.t[0]), t0=float(r.t[0]),
                            f0=f0 if math.isfinite(f0) else None)
            ax.semilogy(a.frequency, a.magnitude, label=f"{name} {symbol}{c}", linewidth=1.0)
            spectra.append(a)
    if spectra:
        _log_limits(ax, spectra[0].frequency, *(a.magnitude for a in spectra))
        if not math.isfinite(f0):
            # no fundamental in the scenario (a signal from a file): the one detected
            f0 = spectra[-1].f0
    _harmonic_markers(ax, f0)
    ax.set_xlabel("frequency f (Hz)")
    ax.set_ylabel(f"{quantity} spectrum ({unit} s)")
    ax.set_title("receiver spectra")
    _eng(ax.xaxis, "Hz")
    ax.legend()
    return ax


# ---------------------------------------------------------------------------------------
# Bar stacks
# ---------------------------------------------------------------------------------------


def bar_stack(r: Any, kind: str, ax: Any) -> Any:
    kinds = ("signals", "gap", "frf")
    if kind not in kinds:
        raise ValueError(f"kind {kind!r}: one of {', '.join(map(repr, kinds))}")
    ax = _axes(ax, "BarStackResult.plot()")
    if kind == "frf":
        f = r.frf["frequency"]
        if len(f) == 0:
            raise ValueError("this run has no FRF (an incident-wave run): kind='signals' or 'gap'")
        ax.loglog(f, np.abs(r.frf["receptance"]), label="receptance", linewidth=1.0)
        mode = r.summary.get("first_mode_hz")
        if isinstance(mode, float) and math.isfinite(mode):
            line = ax.axvline(mode, color="0.5", linestyle=":", linewidth=1.0)
            line.set_gid("first_mode")
        ax.set_xlabel("frequency f (Hz)")
        ax.set_ylabel("receptance |H(f)| (m/N)")
        ax.set_title("frequency response at node 0")
        ax.legend()
        return ax
    if kind == "signals":
        if r.waves is not None:
            for name, y in r.waves.items():
                ax.plot(r.t, y, label=name, linewidth=1.0)
            ax.set_ylabel("displacement (m)")
            unit = "m"
        else:
            ax.plot(r.t, r.force, label="force", linewidth=1.0)
            ax.set_ylabel("force at node 0 (N)")
            unit = "N"
    else:
        for i, g in enumerate(np.asarray(r.gap)):
            ax.plot(r.t, g, label=f"interface {i}", linewidth=1.0)
        ax.set_ylabel("gap (m)")
        unit = "m"
    ax.set_xlabel("time t (s)")
    _eng(ax.xaxis, "s")
    _eng(ax.yaxis, unit)
    ax.legend()
    return ax


# ---------------------------------------------------------------------------------------
# Measured records (cw.analyze)
# ---------------------------------------------------------------------------------------


def analysis(a: Any, kind: str, ax: Any) -> Any:
    kinds = ("record", "spectrum", "harmonics", "fit")
    if kind not in kinds:
        raise ValueError(f"kind {kind!r}: one of {', '.join(map(repr, kinds))}")
    ax = _axes(ax, "Analysis.plot()")
    name = a.records[a.record]["name"] if a.records else ""
    if kind == "record":
        ax.plot(a.t, a.raw, color="0.7", label="record (mean removed)", linewidth=1.0)
        ax.plot(a.t, a.gated, label="gated", linewidth=1.0)
        gate = a.summary.get("gate")
        if gate:
            for edge in ("start", "end"):
                line = ax.axvline(gate[edge], color="0.4", linestyle="--", linewidth=1.0)
                line.set_gid(f"gate_{edge}")
        ax.set_xlabel("time t (s)")
        ax.set_ylabel("record (its unit)")
        ax.set_title(f"record {name}: as read and gated")
        _eng(ax.xaxis, "s")
    elif kind == "spectrum":
        ax.semilogy(a.frequency, a.magnitude, label=f"gated {name}", linewidth=1.0)
        _log_limits(ax, a.frequency, a.magnitude)
        _harmonic_markers(ax, a.f0)
        ax.set_xlabel("frequency f (Hz)")
        ax.set_ylabel("spectrum |X(f)| (unit s)")
        ax.set_title(f"f0 = {a.f0:.6g} Hz{' (detected)' if a.f0_detected else ''}, {a.method}")
        _eng(ax.xaxis, "Hz")
    elif kind == "harmonics":
        rec = a.records[a.record]
        n = np.arange(1, 6, dtype=np.float64)
        amp = a.A[a.record]
        ax.semilogy(n, amp, "o", label="A_n")
        floor = np.array([np.nan] + [_num(rec.get(f"A{k}_floor")) for k in range(2, 6)])
        noise = np.array([np.nan] + [_num(rec.get(f"A{k}_noise_floor")) for k in range(2, 6)])
        leak = np.array([np.nan] + [_num(rec.get(f"A{k}_leakage_floor")) for k in range(2, 6)])
        ax.semilogy(n, floor, "_", markersize=18, markeredgewidth=2, label="floor")
        ax.semilogy(n, noise, "v", markersize=5, label="noise floor")
        ax.semilogy(n, leak, "^", markersize=5, label="leakage floor")
        ax.set_xticks(n)
        ax.set_xticklabels([f"{k} f0" for k in range(1, 6)])
        ax.set_xlabel("harmonic")
        ax.set_ylabel("band amplitude (record unit)")
        ax.set_title(f"harmonics of {name} and their floors")
    else:
        if a.fit is None:
            raise ValueError("no fit: cw.analyze fits A2 against A1^2 over a series of records")
        x = a.A[:, 0] ** 2
        ax.plot(x, a.A[:, 1], "o", label="A2 of each record")
        xs = np.array([0.0, float(np.nanmax(x))])
        slope, icpt = a.fit["slope"], a.fit["intercept"]
        ax.plot(xs, icpt + slope * xs, "-",
                label=f"A2 = {slope:.4g} A1^2 + {icpt:.3g} (R^2 = {a.fit['r_squared']:.4f})")
        ax.set_xlabel("A1^2 (unit^2)")
        ax.set_ylabel("A2 (unit)")
        ax.set_title("A2 against A1^2")
    ax.legend(fontsize=8)
    return ax


def _num(v: Any) -> float:
    return math.nan if v is None else float(v)


# ---------------------------------------------------------------------------------------
# Identification (cw.identify)
# ---------------------------------------------------------------------------------------


def identification(res: Any, observed: Optional[str], ax: Any) -> Any:
    table: Dict[str, np.ndarray] = res.fit_table
    if not table:
        raise ValueError("no fitted curve: a design ranking (design=True) has none")
    keys = res.observed
    key = keys[0] if observed is None else observed
    if key not in keys:
        raise ValueError(f"observed {key!r}: one of {', '.join(map(repr, keys))}")
    conditions = res.conditions
    ax = _axes(ax, "Identification.plot()")
    x_key = conditions[0]
    x = table[x_key]
    # one curve per value of the further conditions (e.g. incident.frequency)
    rest = conditions[1:]
    groups: Dict[tuple, np.ndarray] = {}
    for i in range(len(x)):
        groups.setdefault(tuple(float(table[c][i]) for c in rest), []).append(i)  # type: ignore[arg-type]
    for g, idx in groups.items():
        idx = np.asarray(idx)
        order = idx[np.argsort(x[idx], kind="stable")]
        tag = _tag(rest, g)
        bars = ax.errorbar(x[order], table[key][order], yerr=table[f"sigma_{key}"][order],
                           fmt="o", markersize=4, capsize=2,
                           label="measured" + (f" ({tag})" if tag else ""))
        color = bars[0].get_color()
        ax.plot(x[order], table[f"fitted_{key}"][order], "-", color=color,
                label="fitted" + (f" ({tag})" if tag else ""))
    # the estimates, one line each: `traction stiffness C_N = 1.991e+13 Pa/m`
    est = []
    for k, v in res.get("estimates", {}).items():
        name, unit = _core.quantity(k)
        est.append(f"{name} = {v:.4g} {unit}".rstrip() if v is not None else f"{name}: none")
    ax.set_xlabel(label(x_key))
    ax.set_ylabel(label(key))
    ax.set_title("\n".join(est), fontsize=9)
    ax.legend(fontsize=8)
    return ax


def parse_fit_csv(text: str) -> Dict[str, np.ndarray]:
    """The columns of ``fit.csv`` (a header line, then numbers) as float arrays."""
    lines = [ln for ln in text.splitlines() if ln.strip()]
    if not lines:
        return {}
    head = lines[0].split(",")
    rows = np.array([[float(v) for v in ln.split(",")] for ln in lines[1:]], dtype=np.float64)
    rows = rows.reshape(len(lines) - 1, len(head))
    return {h: np.ascontiguousarray(rows[:, j]) for j, h in enumerate(head)}


# ---------------------------------------------------------------------------------------
# Sweeps
# ---------------------------------------------------------------------------------------


def sweep(table: Any, y: str, x: Optional[str], ax: Any, axes: Optional[Sequence[str]]) -> Any:
    cols = list(table.keys()) if isinstance(table, Mapping) else list(table.columns)
    if axes is None:
        attrs = getattr(table, "attrs", {}) or {}
        axes = attrs.get("axes")
    if axes is None:
        # the columns of a sweep: point, the axes, then the summary keys; without the
        # DataFrame's attrs["axes"] the first axis is the one after `point`
        axes = [cols[1]] if len(cols) > 1 and cols[0] == "point" else []
    axes = list(axes)
    if x is None:
        if not axes:
            raise ValueError("x: name the swept column (the table does not say its axes)")
        x = axes[0]
    for k in (x, y):
        if k not in cols:
            raise ValueError(f"column {k!r} is not in the sweep's table")
    ax = _axes(ax, "contactwave.plot_sweep()")
    xv = np.asarray(table[x], dtype=np.float64)
    yv = np.asarray(table[y], dtype=np.float64)
    rest = [a for a in axes if a != x and a in cols]
    groups: Dict[tuple, List[int]] = {}
    for i in range(len(xv)):
        groups.setdefault(tuple(float(np.asarray(table[c])[i]) for c in rest), []).append(i)
    for g, idx in groups.items():
        ii = np.asarray(idx)
        ii = ii[np.argsort(xv[ii], kind="stable")]
        tag = _tag(rest, g)
        ax.plot(xv[ii], yv[ii], "o-", markersize=3, linewidth=1.0, label=tag or y)
    ax.set_xlabel(label(x))
    ax.set_ylabel(label(y))
    if len(groups) > 1:
        ax.legend(fontsize=8)
    return ax
