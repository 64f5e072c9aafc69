"""contactwave: elastic waves at nonlinear contact interfaces, from Python.

The simulations run in the compiled Rust library (``contactwave._core``); this package
converts inputs and outputs. Every long call releases the GIL. SI units throughout: s, m,
Pa, m/s, Hz, Pa/m, J/m^2; stress is tension-positive, the static pressure ``p0`` is a
compression given as a positive number.

Quick tour::

    import contactwave as cw
    s = cw.load_scenario("examples/rccm_0.82MPa.toml")
    r = cw.run(s)                       # Result: numpy arrays, summary, spectrum, harmonics
    r.summary["A2_over_Ainc"]
    df = cw.sweep("examples/unilateral.toml", {"incident.xi": np.linspace(0.05, 1.2, 47)})

Scenarios are TOML files (docs/scenario.md) or plain dicts with the same keys::

    cw.run({"medium": {"material": "pmma"},
            "interface": {"static_pressure": 0.1e6},
            "incident": {"frequency": 1e6, "cycles": 10, "xi": 0.35}})

A finite crack in 2D (``[model] kind = "solid_2d"``, docs/scenario.md section 2b)::

    r = cw.run("examples/solid_2d/plate_crack_quick.toml")   # Solid2dResult
    r.receivers.shape                   # (n_receivers x components, n_t), m/s
    r.cracks[0]["normal_gap"].shape     # (n_nodes, n_records), m
    r.summary["bottom_A2_over_A1"]
    cw.sweep("examples/solid_2d/plate_crack_quick.toml", {"crack.0.length": [1e-3, 2e-3]})

Invalid scenarios raise ``ValueError`` with the library's message (file, field, value,
allowed range); a numerical failure raises :class:`SimulationError`.
"""

from __future__ import annotations

import json
import math
import os
import warnings
from typing import Any, Callable, Dict, List, Mapping, NamedTuple, Optional, Sequence, Tuple, Union

import numpy as np

from . import _core
from ._core import Scenario, SimulationError

__all__ = [
    "Scenario",
    "SimulationError",
    "HarmonicFloorWarning",
    "Result",
    "BarStackResult",
    "Solid2dResult",
    "Spectrum",
    "load_scenario",
    "scenario_from_dict",
    "scenario_from_toml",
    "run",
    "run_bar_stack",
    "law_curve",
    "fit_power_law",
    "analyze",
    "Analysis",
    "identify",
    "Identification",
    "sweep",
    "plot_sweep",
    "memory_estimate",
    "__version__",
]

__version__: str = _core.__version__

ScenarioLike = Union[Scenario, Mapping[str, Any], str, "os.PathLike[str]"]



class HarmonicFloorWarning(UserWarning):
    """A harmonic amplitude lies within a factor 10 of its analysis floor (what the same
    analysis gives on the response of the linearised interface; summary keys
    ``A2_floor_over_Ainc`` ... ``A5_floor_over_Ainc``, flag ``harmonic_floor_warning``).
    Select a leakage-free method with ``[analysis] method = "pulse_inversion"`` or
    ``"linear_reference"`` (docs/model.md section 6.1)."""


def _warn_near_floor(summary: Mapping[str, Any], stacklevel: int = 3) -> None:
    # at oblique incidence the floors are those of the reflected field's normal component
    prefix = "reflected_normal_" if "angle" in summary else ""
    near = []
    for n in range(2, 6):
        a = summary.get(f"{prefix}A{n}_over_Ainc")
        f = summary.get(f"{prefix}A{n}_floor_over_Ainc")
        if a is not None and f is not None and f > 0 and a < 10 * f:
            near.append(f"{prefix}A{n}")
    if near:
        warnings.warn(
            f"{', '.join(near)} within a factor 10 of the analysis floor "
            f"({prefix}A*_floor_over_Ainc); pulse_inversion or linear_reference remove the "
            "leakage floor",
            HarmonicFloorWarning,
            stacklevel=stacklevel,
        )


#: Points per task when a sweep runs on an executor (see :func:`sweep`).
DEFAULT_CHUNK_SIZE = 64


# ---------------------------------------------------------------------------------------
# Scenarios
# ---------------------------------------------------------------------------------------


def load_scenario(path: Union[str, "os.PathLike[str]"]) -> Scenario:
    """Load and validate a scenario file (TOML, keys of docs/scenario.md).

    Raises ``ValueError`` for an invalid scenario (the message names the file, the field,
    the value and what is allowed) and ``FileNotFoundError`` for a missing file.
    """
    return _core.load_scenario(os.fspath(path))


def _plain(value: Any, key: str, file: str) -> Any:
    """A JSON-ready copy of a scenario value: numpy scalars and arrays become Python
    numbers and lists, paths strings; non-finite numbers are refused with the key."""
    if isinstance(value, Mapping):
        out = {}
        for k, v in value.items():
            if not isinstance(k, str):
                raise ValueError(f"{file}: key {k!r} under `{key or '.'}`: keys must be strings")
            out[k] = _plain(v, f"{key}.{k}" if key else k, file)
        return out
    if isinstance(value, np.ndarray):
        value = value.tolist()
    if isinstance(value, (list, tuple)):
        return [_plain(v, f"{key}[{i}]", file) for i, v in enumerate(value)]
    if isinstance(value, np.generic):
        value = value.item()
    if isinstance(value, os.PathLike):
        value = os.fspath(value)
    if isinstance(value, float) and not math.isfinite(value):
        raise ValueError(f"{file}: field `{key}` = {value}: must be a finite number")
    return value


def _to_json(d: Mapping[str, Any], file: str) -> str:
    if not isinstance(d, Mapping):
        raise TypeError(f"a scenario dict must be a mapping, not {type(d).__name__}")
    return json.dumps(_plain(d, "", file))


def scenario_from_dict(d: Mapping[str, Any], file: str = "<dict>") -> Scenario:
    """Validate a scenario given as a dict with the keys of a scenario file, e.g.
    ``{"medium": {"material": "pmma"}, "interface": {"static_pressure": 1e5}, ...}``.

    Laws are nested dicts: ``"traction": {"law": "rccm", "stiffness": 2e13, "energy": 0.1}``.
    Numbers may be Python or numpy numbers. ``file`` names the scenario in error messages;
    relative paths in it (``incident.path``) resolve against its folder (``<dict>``: the
    working directory). Raises ``ValueError`` naming the field for an invalid dict.
    """
    return _core.scenario_from_json(_to_json(d, file), file)


def scenario_from_toml(text: str, file: str = "<toml>") -> Scenario:
    """Validate a scenario given as TOML text, the contents of a scenario file (e.g. a
    notebook cell's triple-quoted string). ``file`` names it in error messages; relative
    paths in it resolve against its folder (``<toml>``: the working directory). Raises
    ``ValueError`` naming the line of a TOML syntax error, or the field of an invalid value.
    """
    return _core.scenario_from_toml(text, file)


def _as_scenario(s: ScenarioLike) -> Scenario:
    if isinstance(s, Scenario):
        return s
    if isinstance(s, Mapping):
        return scenario_from_dict(s)
    # a string with a line break is a scenario's text, never a file name
    if isinstance(s, str) and "\n" in s:
        return scenario_from_toml(s)
    if isinstance(s, (str, os.PathLike)):
        return load_scenario(s)
    raise TypeError(
        f"expected a Scenario, a dict, a scenario file path or its TOML text, not "
        f"{type(s).__name__}"
    )


# ---------------------------------------------------------------------------------------
# One run
# ---------------------------------------------------------------------------------------


class Spectrum(NamedTuple):
    """Amplitude spectra of the incident and reflected particle velocity (``|X(f)| dt``,
    m/s x s) on one frequency grid (Hz), up to 6 times the highest input frequency."""

    frequency: np.ndarray
    incident: np.ndarray
    reflected: np.ndarray


class Result:
    """Everything one run produces (see :func:`run`). All arrays are float64 numpy arrays.

    Interface histories at x = 0, on one time grid (columns of ``timeseries.csv``):
    ``t`` (s), ``gap`` (m, opening-positive), ``contact_stress`` (Pa), ``beta`` (adhesion,
    -), ``incident_stress``, ``reflected_stress``, ``transmitted_stress`` (Pa).

    Probe histories at ``probe_x`` < 0 (columns of ``probe.csv``): ``probe_t`` (s),
    ``probe_incident_stress``, ``probe_reflected_stress`` (Pa),
    ``probe_incident_velocity``, ``probe_reflected_velocity`` (m/s),
    ``probe_displacement`` (m).

    ``summary``: dict with the keys of ``summary.json`` in order (``scenario``, then the
    scalars: ``xi``, ``A1_over_Ainc`` ... ``A5_over_Ainc``, ``A2_over_A1``, ``beta_star``,
    ``beta_end``, energies, ..., ``analysis_method`` (code), the floors
    ``A2_floor_over_Ainc`` ... ``A5_floor_over_Ainc`` and ``harmonic_floor_warning``);
    ``analysis_method``: the name of the analysis method (``[analysis] method``);
    ``floor``: the band amplitudes of that method on the linear response (m/s, keys as
    :meth:`harmonics`' ``A1`` ...); ``dt``: time step (s); ``scenario``: the Scenario run.
    A summary with ``harmonic_floor_warning = 1`` makes :func:`run` emit a
    :class:`HarmonicFloorWarning`.

    With a tangential part (a shear wave, a tangential law or a static shear; docs/model.md
    section 13) ``shear`` is a dict of numpy arrays on the same time grid (the columns of
    ``shear.csv``): ``shear_gap`` ([u]_T, m), ``slip`` (m), ``shear_stress`` (Pa),
    ``friction_limit`` (mu N, Pa), ``slip_state`` (0 stick, +1/-1 slipping, NaN free),
    ``shear_incident_stress``, ``shear_reflected_stress``, ``shear_transmitted_stress``
    (Pa), plus ``shear_reflected_bands`` / ``shear_transmitted_bands`` (m/s) and
    ``shear_A_inc`` (m/s); ``None`` otherwise. The summary then has the ``shear_*``,
    ``friction_*`` and ``slip_*`` keys.
    """

    t: np.ndarray
    gap: np.ndarray
    contact_stress: np.ndarray
    beta: np.ndarray
    incident_stress: np.ndarray
    reflected_stress: np.ndarray
    transmitted_stress: np.ndarray
    probe_t: np.ndarray
    probe_incident_stress: np.ndarray
    probe_reflected_stress: np.ndarray
    probe_incident_velocity: np.ndarray
    probe_reflected_velocity: np.ndarray
    probe_displacement: np.ndarray
    probe_x: float
    dt: float
    summary: Dict[str, Any]

    _ARRAYS = (
        "t",
        "gap",
        "contact_stress",
        "beta",
        "incident_stress",
        "reflected_stress",
        "transmitted_stress",
        "probe_t",
        "probe_incident_stress",
        "probe_reflected_stress",
        "probe_incident_velocity",
        "probe_reflected_velocity",
        "probe_displacement",
    )

    _SHEAR = (
        "shear_gap",
        "slip",
        "shear_stress",
        "friction_limit",
        "slip_state",
        "shear_incident_stress",
        "shear_reflected_stress",
        "shear_transmitted_stress",
        "shear_reflected_bands",
        "shear_transmitted_bands",
        "shear_A_inc",
    )

    def __init__(self, raw: Dict[str, Any], scenario: Scenario) -> None:
        self.scenario = scenario
        for k in self._ARRAYS:
            setattr(self, k, raw[k])
        self.probe_x = raw["probe_x"]
        self.dt = raw["dt"]
        self.summary = raw["summary"]
        self._spectrum = Spectrum(*raw["spectrum"])
        self._bands = (raw["incident_bands"], raw["reflected_bands"], raw["A_inc"])
        self.analysis_method: str = raw.get("analysis_method", "band_peak")
        self.floor: Dict[str, float] = dict(raw.get("floor_bands", {}))
        self.shear: Optional[Dict[str, Any]] = None
        if "shear_gap" in raw:
            self.shear = {k: raw[k] for k in self._SHEAR if k in raw}

    def spectrum(self) -> Spectrum:
        """The spectra of ``spectrum.csv``: ``(frequency, incident, reflected)`` arrays."""
        return self._spectrum

    def harmonics(self) -> Dict[str, float]:
        """Band amplitudes of the reflected particle velocity (m/s): ``A1`` ... ``A5``
        (band ``[n f0 - f0/2, n f0 + f0/2)``), ``Asub`` (f0/2) and, for two-tone bursts,
        ``Af2``, ``Asum``, ``Adiff``; the incident amplitude ``A_inc`` (m/s); the ratios
        ``A1_over_Ainc`` ... ``A5_over_Ainc``, ``A2_over_A1``, ``beta_star`` (A2/A1^2);
        and the incident burst's own bands as ``incident_A1`` ... ``incident_Asub``."""
        inc, refl, a_inc = self._bands
        h: Dict[str, float] = dict(refl)
        h["A_inc"] = a_inc
        for n in range(1, 6):
            h[f"A{n}_over_Ainc"] = refl[f"A{n}"] / a_inc if a_inc > 0 else math.nan
        a1, a2 = refl["A1"], refl["A2"]
        h["A2_over_A1"] = a2 / a1 if a1 > 0 else 0.0
        h["beta_star"] = a2 / (a1 * a1) if a1 > 0 else 0.0
        for k, v in inc.items():
            h[f"incident_{k}"] = v
        return h

    def to_pandas(self, table: str = "timeseries") -> Any:
        """A pandas DataFrame of one table, indexed by its time (s) or frequency (Hz):
        ``"timeseries"`` (interface histories: ``gap``, ``contact_stress``, ...),
        ``"probe"`` (the probe's histories, without the ``probe_`` prefix; ``attrs
        ["probe_x"]``), ``"spectrum"`` (``incident``, ``reflected``) or ``"shear"``.
        ``attrs["units"]`` maps each column (and the index) to its SI unit. Needs pandas
        (the ``pandas`` extra), else ``ImportError`` naming it."""
        from ._frames import half_space_pandas

        return half_space_pandas(self, table)

    def to_xarray(self) -> Any:
        """An xarray Dataset: the interface histories on coordinate ``time`` (s), the
        probe's on ``probe_time`` (s), the spectra (``incident_spectrum``,
        ``reflected_spectrum``, m) on ``frequency`` (Hz); every variable and coordinate
        has ``attrs["units"]``; the summary's numbers are the Dataset's attributes. Needs
        xarray (the ``xarray`` extra), else ``ImportError`` naming it."""
        from ._frames import half_space_xarray

        return half_space_xarray(self)

    def plot(self, kind: str = "signals", ax: Any = None) -> Any:
        """One matplotlib panel into ``ax`` (a new figure when ``None``); returns the
        Axes (needs the ``plot`` extra). ``kind``: ``"signals"`` (incident, reflected and
        transmitted stress at the interface against ``t``), ``"probe"`` (the probe's
        incident and reflected velocities), ``"gap"``, ``"spectrum"`` (``spectrum()``'s
        incident and reflected spectra, log scale, dotted markers at n f0)."""
        from ._plot import half_space

        return half_space(self, kind, ax)

    def __repr__(self) -> str:
        s = self.summary
        if "angle" in s:
            # oblique incidence: the outgoing waves
            return (
                f"Result(scenario={s.get('scenario')!r}, samples={len(self.t)}, "
                f"angle={s.get('angle'):.6g}, "
                f"reflected_P_A1_over_Ainc={s.get('reflected_P_A1_over_Ainc'):.6g}, "
                f"reflected_SV_A1_over_Ainc={s.get('reflected_SV_A1_over_Ainc'):.6g})"
            )
        if self.shear is not None and "A2_over_Ainc" not in s:
            return (
                f"Result(scenario={s.get('scenario')!r}, samples={len(self.t)}, "
                f"friction_ratio={s.get('friction_ratio'):.6g}, "
                f"shear_A3_over_A1={s.get('shear_A3_over_A1'):.6g})"
            )
        return (
            f"Result(scenario={s.get('scenario')!r}, samples={len(self.t)}, "
            f"xi={s.get('xi'):.6g}, A2_over_Ainc={s.get('A2_over_Ainc'):.6g})"
        )


class BarStackResult:
    """Everything one bar-stack run produces (see :func:`run_bar_stack`): float64 numpy
    arrays on one time grid ``t`` (s, 0 at the start of the source).

    Node 0 (the first end): ``force`` (N; 0 for an incident-wave run; the reaction with an
    imposed displacement), ``displacement`` (m, from the static equilibrium),
    ``acceleration`` (m/s^2). Interfaces (rows in stack order, the obstacle last; columns
    the samples): ``gap`` (m), ``pressure`` (Pa, ``-sigma``), ``beta`` (-), ``stiffness``
    (Pa/m, ``inf`` for a closed rigid branch). ``frf``: dict ``frequency`` (Hz),
    ``receptance`` (m/N), ``receptance_phase`` (rad), ``accelerance`` ((m/s^2)/N),
    ``force_db`` (dB re the force spectrum's peak; the other three are NaN where it is below
    -40 dB: the force carries no energy there), empty arrays for an incident-wave run. ``waves``: for an incident-wave run a dict
    ``incident``, ``reflected`` and (transparent far end) ``transmitted`` displacements
    (m), else ``None``. ``shear``: for a stack with a transverse field (shear waves,
    docs/model.md section 9.7) a dict ``gap``, ``stress``, ``slip``, ``slip_state`` (one
    row per interface: m, Pa, m, -), ``friction_dissipation``, ``damage_dissipation``
    (J per interface) and ``waves`` (shear ``incident``, ``reflected``, ``transmitted``
    displacements, or ``None``), else ``None``. ``probes``: ``{name: {"x",
    "displacement", "velocity", "acceleration", "stress"}}`` (and ``shear_displacement``,
    ``shear_velocity``, ``shear_stress`` with a transverse field). ``static_pressure``:
    list of ``p0`` per interface (Pa);
    ``dt`` (s); ``summary``: the keys of ``summary.json`` (per-interface values as
    ``key_0``, ``key_1``, ...).
    """

    t: np.ndarray
    force: np.ndarray
    displacement: np.ndarray
    acceleration: np.ndarray
    gap: np.ndarray
    pressure: np.ndarray
    beta: np.ndarray
    stiffness: np.ndarray
    frf: Dict[str, np.ndarray]
    waves: Optional[Dict[str, np.ndarray]]
    shear: Optional[Dict[str, Any]]
    probes: Dict[str, Dict[str, Any]]
    static_pressure: List[float]
    dt: float
    summary: Dict[str, Any]

    _KEYS = (
        "t",
        "force",
        "displacement",
        "acceleration",
        "gap",
        "pressure",
        "beta",
        "stiffness",
        "frf",
        "waves",
        "shear",
        "probes",
        "static_pressure",
        "dt",
        "summary",
    )

    def __init__(self, raw: Dict[str, Any]) -> None:
        for k in self._KEYS:
            setattr(self, k, raw[k])

    def to_pandas(self) -> Any:
        """A pandas DataFrame indexed by ``t`` (s): ``force``, ``displacement``,
        ``acceleration`` and per interface ``gap_i``, ``pressure_i``, ``beta_i``,
        ``stiffness_i`` (the columns of ``timeseries.csv``); ``attrs["units"]`` gives
        the units. Needs pandas (the ``pandas`` extra)."""
        from ._frames import bar_stack_pandas

        return bar_stack_pandas(self)

    def to_xarray(self) -> Any:
        """An xarray Dataset on coordinates ``time`` (s) and ``interface``: ``force``,
        ``displacement``, ``acceleration`` (time) and ``gap``, ``pressure``, ``beta``,
        ``stiffness`` (interface, time), each with ``attrs["units"]``. Needs xarray (the
        ``xarray`` extra)."""
        from ._frames import bar_stack_xarray

        return bar_stack_xarray(self)

    def plot(self, kind: str = "signals", ax: Any = None) -> Any:
        """One matplotlib panel into ``ax`` (a new figure when ``None``); returns the
        Axes (needs the ``plot`` extra). ``kind``: ``"signals"`` (the force at node 0, or
        the waves of an incident-wave run), ``"gap"`` (each interface's gap), ``"frf"``
        (the receptance's magnitude, log-log, the first mode dotted)."""
        from ._plot import bar_stack

        return bar_stack(self, kind, ax)

    def __repr__(self) -> str:
        s = self.summary
        main = (
            f"A2_over_Ainc={s.get('A2_over_Ainc'):.6g}"
            if self.waves is not None
            else f"first_mode_hz={s.get('first_mode_hz'):.6g}"
        )
        return (
            f"BarStackResult(scenario={s.get('scenario')!r}, samples={len(self.t)}, "
            f"interfaces={self.gap.shape[0]}, {main})"
        )


def _position(what: str, name: str, names: Sequence[str]) -> int:
    """The index of ``name`` in ``names``; a ``ValueError`` naming the valid ones if
    absent."""
    try:
        return list(names).index(name)
    except ValueError:
        valid = ", ".join(names) if len(names) else "none in this run"
        raise ValueError(f"{what} {name!r}: not in this run ({valid})") from None


from ._frames import unique as _unique  # noqa: E402


def _rows(
    records: Any, names: Sequence[str], components: Sequence[str], x: Any, z: Any, nt: int
) -> Any:
    """One row per point and component (point-major, the order of ``receivers.csv``):
    the records ``(n_points * n_components, n_t)`` and, per row, the point's name, the
    component and the point's x and z (m)."""
    names, components = list(names), list(components)
    k = len(components)
    rows = np.asarray(records, dtype=np.float64).reshape(len(names) * k, nt)
    return (
        rows,
        [n for n in names for _ in range(k)],
        components * len(names),
        np.repeat(np.asarray(x, dtype=np.float64), k),
        np.repeat(np.asarray(z, dtype=np.float64), k),
    )


def _row(what: str, name: str, component: str, names: Sequence[str], comps: Sequence[str]) -> int:
    """The row of point ``name``, component ``component``; a ``ValueError`` naming the
    valid names or components if either is absent."""
    _position(what, name, _unique(names))
    _position(f"{what} component", component, _unique(comps))
    return next(i for i, (n, c) in enumerate(zip(names, comps)) if n == name and c == component)


class Solid2dResult:
    """Everything one 2D run produces (``[model] kind = "solid_2d"``, docs/scenario.md
    section 2b; docs/model.md section 15), as float64 numpy arrays.

    ``t``: times of the receiver samples (s, the half levels of the time step).
    ``receivers``: the velocity records, shape ``(n_receivers, n_t)`` (m/s), one row per
    receiver and component, in the column order of ``receivers.csv``; per row,
    ``receiver_names`` (the scenario's name), ``receiver_components`` (``"x"``, ``"z"``
    or ``"y"``) and the position ``receiver_x``, ``receiver_z`` (m). ``components``
    names the run's velocity components (``["x", "z"]`` in P-SV runs, ``["y"]`` in SH
    runs). ``stresses``: the stress receivers' records, shape ``(n_stress_receivers,
    n_t)`` (Pa, tension positive, dynamic), one row per stress receiver and component;
    per row ``stress_names``, ``stress_components`` (``"xx"``, ``"zz"``, ``"xz"`` or
    ``"yx"``, ``"yz"``) and ``stress_x``, ``stress_z`` (m).
    ``cracks``: one dict per crack with ``position``
    (m along it, ``(n_nodes,)``), the nodes' coordinates ``x``, ``z`` (m, ``(n_nodes,)``),
    ``time`` (s, ``(n_records,)``) and ``normal_gap``,
    ``tangential_gap`` (m), ``normal_stress``, ``shear_stress`` (Pa, tension positive,
    ``-p0`` at rest), ``adhesion`` and ``state`` (0 open, 1 stick, 2 slip, or closed on a
    frictionless crack) of shape
    ``(n_nodes, n_records)``. ``dt`` (s);
    ``summary``: the numbers of ``summary.json`` (the CLI's file adds ``scenario`` and
    ``provenance``; here ``scenario`` is the :class:`Scenario` run, ``None`` for a raw
    record). ``snapshots``: with a ``[snapshots]`` table,
    the wavefield frames on their pixel grid, shape ``(n_snapshots, n_z, n_x)`` (m/s, the
    top row first; ``(0, 0, 0)`` without), at ``snapshot_times`` (s), pixel centres
    ``snapshot_x``, ``snapshot_z`` (m); ``snapshot_field`` names the value drawn.
    """

    t: np.ndarray
    receivers: np.ndarray
    receiver_names: List[str]
    receiver_components: List[str]
    receiver_x: np.ndarray
    receiver_z: np.ndarray
    components: List[str]
    stresses: np.ndarray
    stress_names: List[str]
    stress_x: np.ndarray
    stress_z: np.ndarray
    stress_components: List[str]
    cracks: List[Dict[str, np.ndarray]]
    dt: float
    summary: Dict[str, Any]
    snapshots: np.ndarray
    snapshot_times: np.ndarray
    snapshot_x: np.ndarray
    snapshot_z: np.ndarray
    snapshot_field: str

    def __init__(self, raw: Dict[str, Any], scenario: Optional[Scenario] = None) -> None:
        self.scenario = scenario
        self.t = raw["t"]
        nt = len(self.t)
        self.components = list(raw["components"])
        (
            self.receivers,
            self.receiver_names,
            self.receiver_components,
            self.receiver_x,
            self.receiver_z,
        ) = _rows(raw["receivers"], raw["receiver_names"], self.components,
                  raw["receiver_x"], raw["receiver_z"], nt)
        (
            self.stresses,
            self.stress_names,
            self.stress_components,
            self.stress_x,
            self.stress_z,
        ) = _rows(raw["stresses"], raw["stress_names"], raw["stress_components"],
                  raw["stress_x"], raw["stress_z"], nt)
        self.cracks = [dict(c) for c in raw["cracks"]]
        self.dt = raw["dt"]
        self.summary = raw["summary"]
        self.snapshot_times = np.asarray(raw["snapshot_times"], dtype=np.float64)
        self.snapshot_x = np.asarray(raw["snapshot_x"], dtype=np.float64)
        self.snapshot_z = np.asarray(raw["snapshot_z"], dtype=np.float64)
        self.snapshot_field = raw["snapshot_field"]
        frames = np.asarray(raw["snapshots"], dtype=np.float64)
        self.snapshots = frames.reshape(
            len(self.snapshot_times), len(self.snapshot_z), len(self.snapshot_x)
        )

    def velocity(self, name: str, component: str) -> np.ndarray:
        """The velocity (m/s) of receiver ``name`` along ``component`` (``x``, ``z`` or
        ``y``). An unknown name or component is a ``ValueError`` listing the valid ones."""
        return self.receivers[
            _row("receiver", name, component, self.receiver_names, self.receiver_components)
        ]

    def stress(self, name: str, component: str) -> np.ndarray:
        """The stress (Pa) of stress receiver ``name``, component ``component`` (``xx``,
        ``zz``, ``xz``, ``yx`` or ``yz``). An unknown name or component is a
        ``ValueError`` listing the valid ones."""
        return self.stresses[
            _row("stress receiver", name, component, self.stress_names, self.stress_components)
        ]

    def to_pandas(self) -> Any:
        """A pandas DataFrame indexed by ``t`` (s) with the columns of
        ``receivers.csv``: ``<name>_v<x|z|y>`` (m/s) and ``<name>_s<xx|zz|xz|yx|yz>``
        (Pa); ``attrs["units"]`` gives the units. Needs pandas (the ``pandas`` extra)."""
        from ._frames import solid_2d_pandas

        return solid_2d_pandas(self)

    def to_xarray(self) -> Any:
        """An xarray Dataset: ``velocity`` (receiver, component, time; m/s), ``stress``
        (stress_receiver, stress_component, time; Pa), ``snapshot`` (snapshot_time, z,
        x; m/s) and per crack ``crack<k>_normal_gap`` ... on (``crack<k>_position`` m,
        ``crack<k>_time`` s); coordinates ``time`` (s), ``x``, ``z`` (m, the snapshot
        pixel centres), all with ``attrs["units"]``; a part the run does not have (no
        velocity or stress receivers, no ``[snapshots]``) is left out, with no empty
        dimension. Needs xarray (the ``xarray`` extra)."""
        from ._frames import solid_2d_xarray

        return solid_2d_xarray(self)

    def plot(
        self, kind: str = "receivers", ax: Any = None, receivers: Any = None, component: Any = None
    ) -> Any:
        """One matplotlib panel into ``ax`` (a new figure when ``None``); returns the
        Axes (needs the ``plot`` extra). ``kind``: ``"receivers"`` (the records against
        ``t``) or ``"spectrum"`` (each record's spectrum as ``cw.analyze`` gives it, log
        scale, dotted markers at n f0); ``receivers`` (a name or names) and ``component``
        (``"x"``, ``"z"``, ``"y"``, or a stress component, or a list) choose the records:
        by default every velocity receiver, or every stress receiver in a run that has
        only those; names of stress receivers only draw stresses (Pa)."""
        from ._plot import solid_2d

        return solid_2d(self, kind, ax, receivers, component)

    def __repr__(self) -> str:
        s = self.summary
        return (
            f"Solid2dResult(scenario={self.scenario.file if self.scenario else None!r}, "
            f"receivers={_unique(self.receiver_names)}, "
            f"cracks={len(self.cracks)}, steps={len(self.t)}, "
            f"energy_closure_error={s.get('energy_closure_error'):.3g})"
        )


#: How each kind of scenario's record (``_core.run``) becomes a Python result: one entry
#: per kind registered in the library (``contactwave::model::KINDS``).
_RESULTS = {
    "half_space": lambda raw, s: Result(raw, s),
    "bar_stack": lambda raw, s: BarStackResult(raw),
    "solid_2d": lambda raw, s: Solid2dResult(raw, s),
}


def run_bar_stack(
    scenario: Union[Mapping[str, Any], str, "os.PathLike[str]"], file: str = "<dict>"
) -> BarStackResult:
    """Simulate one bar-stack scenario (``[model] kind = "bar_stack"``, docs/scenario.md
    section 2), given as a TOML file path or a dict with the same keys, and return a
    :class:`BarStackResult`: the hammer test (FRF, first mode, harmonics, contact
    pressures) or the incident-wave run (reflected and transmitted waves).

    ``file`` names a dict in error messages and resolves its relative paths. The GIL is
    released while the simulation runs. Raises ``ValueError`` for an invalid scenario and
    :class:`SimulationError` for a numerical failure.
    """
    if isinstance(scenario, Mapping):
        s = scenario_from_dict(scenario, file)
    elif isinstance(scenario, (str, os.PathLike, Scenario)):
        s = _as_scenario(scenario)
    else:
        raise TypeError(
            f"expected a bar-stack dict or scenario file path, not {type(scenario).__name__}"
        )
    if s.kind != "bar_stack":
        raise ValueError(
            f"{s.file}: not a bar-stack scenario ([model] kind = \"bar_stack\"); use run()"
        )
    return BarStackResult(_core.run(s))


def run(scenario: ScenarioLike) -> Union[Result, BarStackResult, "Solid2dResult"]:
    """Simulate one scenario (a :class:`Scenario`, a dict, a TOML file path or its TOML
    text) and return a :class:`Result`: the arrays of ``timeseries.csv`` and
    ``probe.csv``, the summary of ``summary.json``, ``spectrum()`` and ``harmonics()``.
    A bar-stack scenario (``[model] kind = "bar_stack"``) gives a :class:`BarStackResult`
    (as :func:`run_bar_stack`), a 2D scenario (``kind = "solid_2d"``) a
    :class:`Solid2dResult`.

    Values that are legal but almost surely a unit slip (``frequency = 1`` meant as
    1 MHz, a width of 40 m meant as mm) give a ``UserWarning`` each, naming the key
    (:attr:`Scenario.warnings`). The GIL is released while the simulation runs; Ctrl-C
    stops it (``KeyboardInterrupt``). Raises ``ValueError`` for an invalid scenario (file,
    field, value, allowed range), also for a 2D grid beyond the memory budget (naming the
    key to change, e.g. ``model.element_size``), and :class:`SimulationError` for a
    numerical failure.
    """
    s = _as_scenario(scenario)
    for w in s.warnings:  # legal values that are almost surely a unit slip
        warnings.warn(w, UserWarning, stacklevel=2)
    raw = _core.run(s)
    result = _RESULTS[raw["kind"]](raw, s)
    if raw["kind"] == "half_space":
        _warn_near_floor(result.summary)
    return result


def _bench_simulate(scenario: ScenarioLike, n: int) -> List[float]:
    """Wall times (s) of ``n`` runs of the Rust ``simulate`` alone (no conversion to
    Python), for measuring the overhead of :func:`run`."""
    return _core.bench_simulate(_as_scenario(scenario), int(n))


# ---------------------------------------------------------------------------------------
# Laws and fits
# ---------------------------------------------------------------------------------------

#: What a bare law dict is completed with to make a scenario (only the law is used).
_LAW_CARRIER = {"medium": {"material": "pmma"}, "incident": {"frequency": 1e6, "amplitude": 1.0}}


def law_curve(scenario_or_law: Union[ScenarioLike, Mapping[str, Any]], gap: Any) -> np.ndarray:
    """Stress (Pa, tension-positive) of a contact law at each gap (m, opening-positive).

    ``scenario_or_law``: a scenario (Scenario, dict or path), or a law dict with the keys
    of a scenario's ``[interface]`` table, e.g. ``{"static_pressure": 1e5, "compression":
    {"law": "power", "c": 1.81e10, "m": 0.35}, "traction": {"law": "rccm", "stiffness":
    2e13, "energy": 0.1}}`` (error messages then name the fields ``interface.*``).

    The stress is that of the monotone-loading curve: damage evolves in its
    rate-independent limit as the gap increases through the given values (in increasing
    order, whatever their order in ``gap``), as in ``contactwave law``. On a rigid
    compression branch, gaps <= 0 give ``-p0``; on a bonded traction branch, openings
    give 0 (a constraint sets the stress there). Returns an array shaped like ``gap``.
    """
    if isinstance(scenario_or_law, Mapping) and not (
        {"medium", "interface", "incident"} & set(scenario_or_law)
    ):
        d = dict(_LAW_CARRIER)
        d["interface"] = dict(scenario_or_law)
        s = scenario_from_dict(d, file="<law>")
    else:
        s = _as_scenario(scenario_or_law)  # type: ignore[arg-type]
    g = np.asarray(gap, dtype=np.float64)
    out = _core.law_curve(s, np.ascontiguousarray(g.ravel()))
    return out.reshape(g.shape)


def fit_power_law(pressure: Any, stiffness: Any) -> Dict[str, float]:
    """Least-squares fit of ``K = C p^m`` on ``(ln p, ln K)`` (thesis eq. 4.4): pressures
    in Pa, stiffnesses in Pa/m, all > 0, at least two distinct pressures. Returns
    ``{"c": C (Pa^(1-m)/m), "m": m, "r2": coefficient of determination}``."""
    p = np.ascontiguousarray(np.asarray(pressure, dtype=np.float64).ravel())
    k = np.ascontiguousarray(np.asarray(stiffness, dtype=np.float64).ravel())
    return _core.fit_power_law(p, k)


from .measured import Analysis, analyze  # noqa: E402  (needs HarmonicFloorWarning above)


from .identification import Identification, identify  # noqa: E402


# ---------------------------------------------------------------------------------------
# Sweeps
# ---------------------------------------------------------------------------------------


def _base(base: ScenarioLike) -> Tuple[str, str]:
    """(table as JSON, path standing for it) of a sweep's base scenario."""
    if isinstance(base, Mapping):
        return _to_json(base, "<dict>"), "<dict>"
    # a string with a line break is a scenario's text (as for `run`), never a file name
    if isinstance(base, str) and "\n" in base:
        return _core.toml_table_json(base, "<toml>"), "<toml>"
    if isinstance(base, (str, os.PathLike)):
        # the table as written: the sweep validates every point (as the CLI does), so a
        # base that lacks a key every point sets is fine
        return _core.table_json(os.fspath(base)), os.fspath(base)
    s = _as_scenario(base)
    return s.to_json(), os.fspath(s.path)


def _axes(axes: Union[Mapping[str, Any], Sequence[Tuple[str, Any]]]) -> List[Tuple[str, List[float]]]:
    items = axes.items() if isinstance(axes, Mapping) else axes
    out = []
    for key, values in items:
        if isinstance(values, str) or (
            isinstance(values, (list, tuple)) and any(isinstance(x, str) for x in values)
        ):
            # unit strings ("1 MHz") converted to SI for the key
            seq = [values] if isinstance(values, str) else values
            values = [_core.si_value(str(key), x) for x in seq]
        v = np.asarray(values, dtype=np.float64)
        if v.ndim > 1:
            raise ValueError(f"axis `{key}`: values must be one-dimensional, not shape {v.shape}")
        out.append((str(key), v.ravel().tolist()))
    if not out:
        raise ValueError("axes: give at least one axis (dotted key -> values)")
    return out


def memory_estimate(
    base: ScenarioLike, axes: Union[Mapping[str, Any], Sequence[Tuple[str, Any]]]
) -> np.ndarray:
    """The memory one run of each sweep point needs, bytes (what :func:`sweep` checks
    against a Dask worker's memory limit before it submits anything), estimated without
    running: for ``solid_2d`` scenarios the mesh and its stepping state, the time step the
    plan will take and the recorded series (twice for a method with a second run, plus the
    snapshots); NaN for the kinds that give no estimate. ``base`` and ``axes`` as for
    :func:`sweep`; every point is validated (``ValueError`` naming the field and the point).
    """
    base_json, base_path = _base(base)
    _points, _hash, memory = _core.sweep_plan(base_json, base_path, _axes(axes))
    return memory


def _check_worker_memory(
    client: Any, memory: np.ndarray, points: np.ndarray, parameters: List[str]
) -> None:
    """Refuse a sweep a Dask worker could not hold: a task runs its points one after the
    other, so it needs the largest estimate of its chunk, and a worker runs as many tasks
    at once as it has threads. Every worker with a memory limit must give each of its
    threads that much (the scheduler may send any task to any worker)."""
    known = np.where(np.isnan(memory), 0.0, memory)
    if len(known) == 0 or not np.any(known > 0):
        return
    i = int(np.argmax(known))
    need = float(known[i])
    try:
        workers = client.scheduler_info().get("workers", {})
    except Exception:  # noqa: BLE001 - an executor that cannot tell: nothing to check
        return
    for address, w in sorted(workers.items()):
        limit = w.get("memory_limit") or 0
        threads = max(int(w.get("nthreads") or 1), 1)
        if limit and need * threads > limit:
            at = ", ".join(f"{k} = {float(points[i, k_i])!r}" for k_i, k in enumerate(parameters))
            raise ValueError(
                f"sweep point {i} ({at}) needs about {need / 1e6:.0f} MB of memory per "
                f"task, and Dask worker {address} runs {threads} task(s) at once within a "
                f"memory_limit of {limit / 1e6:.0f} MB ({need * threads / 1e6:.0f} MB needed): "
                "nothing was submitted; give the workers more memory or fewer threads "
                "(LocalCluster(memory_limit=..., threads_per_worker=1)), or coarsen the "
                "scenario (model.element_size, model.duration)"
            )


# set beside CONTACTWAVE_MEMORY_BUDGET when a Dask worker set it (not the user)
_BUDGET_MARK = "CONTACTWAVE_MEMORY_BUDGET_FROM_WORKER"


def _worker_budget() -> None:
    """On a Dask worker, the memory budget of the runs (``CONTACTWAVE_MEMORY_BUDGET``,
    unless set already) becomes each thread's share of the worker's ``memory_limit``, so
    that every point checks its estimate against what its worker can give before it
    starts (a refused point fails with the message, the others go on)."""
    # a budget the user set stands; one a worker set (an in-process worker shares the
    # client's environment, and processes spawned from it inherit it) is recomputed
    if "CONTACTWAVE_MEMORY_BUDGET" in os.environ and _BUDGET_MARK not in os.environ:
        return
    try:
        from distributed import get_worker

        worker = get_worker()
    except (ImportError, ValueError):
        return
    # (distributed >= 2022.4 keeps it in the worker's memory manager)
    limit = getattr(getattr(worker, "memory_manager", None), "memory_limit", None)
    limit = limit or getattr(worker, "memory_limit", None)
    state = getattr(worker, "state", None)
    threads = getattr(state, "nthreads", None) or getattr(worker, "nthreads", None) or 1
    if limit:
        os.environ["CONTACTWAVE_MEMORY_BUDGET"] = str(int(limit // max(int(threads), 1)))
        os.environ[_BUDGET_MARK] = "1"


def _run_chunk(
    base_json: str, base_path: str, parameters: List[str], points: np.ndarray
) -> Tuple[List[str], np.ndarray, List[Tuple[int, str]]]:
    """One distributed task: run the sweep points ``points`` (rows of axis values)."""
    from contactwave import _core as core

    _worker_budget()
    return core.run_points(base_json, base_path, parameters, points)


def _is_dask_client(executor: Any) -> bool:
    return hasattr(executor, "gather") and hasattr(executor, "scatter")


def _run_on_executor(
    executor: Any,
    base_json: str,
    base_path: str,
    parameters: List[str],
    points: np.ndarray,
    chunk_size: int,
    progress: Optional[Callable[[int, int], Any]] = None,
) -> List[Tuple[List[str], np.ndarray, List[Tuple[int, str]]]]:
    chunks = [
        np.ascontiguousarray(points[i : i + chunk_size])
        for i in range(0, len(points), chunk_size)
    ]
    dask = _is_dask_client(executor)
    kw = {"pure": False} if dask else {}
    futures = [
        executor.submit(_run_chunk, base_json, base_path, parameters, c, **kw) for c in chunks
    ]
    try:
        if progress is None:
            if dask:
                return list(executor.gather(futures))
            return [f.result() for f in futures]
        # results in grid order; progress counts the points of the chunks done so far
        out = []
        done = 0
        progress(0, len(points))
        for f, c in zip(futures, chunks):
            out.append(f.result())
            done += len(c)
            progress(done, len(points))
        return out
    except BaseException:
        for f in futures:
            f.cancel()
        raise


def sweep(
    base: ScenarioLike,
    axes: Union[Mapping[str, Any], Sequence[Tuple[str, Any]]],
    executor: Any = None,
    *,
    threads: Optional[int] = None,
    chunk_size: int = DEFAULT_CHUNK_SIZE,
    as_frame: Optional[bool] = None,
    progress: Union[None, bool, Callable[[int, int], Any]] = None,
) -> Any:
    """Run a parameter sweep: the grid of ``axes`` over the ``base`` scenario.

    ``base``: a Scenario, a dict, a scenario file path or its TOML text (a string with a
    line break), of any kind: half-space, bar stack (the rows carry its summary keys:
    ``first_mode_hz``, ``A2_over_A1``, ``min_contact_pressure``, ...; or the
    reflected-wave keys of an ``[incident]`` run) or 2D (``solid_2d``: the rows carry
    ``<receiver>_A1`` ... ``<receiver>_A2_over_A1``, ``crack_max_gap_<i>``, ``nodes``,
    ``steps``, ...). ``axes``: maps dotted scenario keys to value arrays, e.g.
    ``{"incident.xi": np.linspace(0.05, 1.2, 47), "interface.traction.stiffness": [1e12,
    1e13]}`` or, for a 2D base, ``{"crack.0.length": [1e-3, 2e-3],
    "crack.0.static_pressure": ["0.5 MPa", "1 MPa"], "crack.0.tangential.friction": [0.1,
    0.3], "source.0.angle": [0, 20]}`` (the index of an array's only table may be left
    out: ``crack.length``; ``mu`` is ``friction``; values may be unit strings); several
    axes form a grid, first axis slowest, exactly like a sweep file's ``[[axis]]``
    tables. Every point is validated before anything runs (``ValueError`` naming the
    field and the point; two axes setting one value are refused).

    ``executor=None``: all local cores (``threads`` to limit them), in Rust with the GIL
    released; Ctrl-C stops the sweep (``KeyboardInterrupt``); ``progress(done, total)``,
    if given, is called on the calling thread as points finish (at most every 50 ms, and
    with ``(total, total)`` exactly once at the end; an exception in it stops the sweep
    like Ctrl-C); with an executor it is called as the chunks come back, in grid order.
    ``progress=True`` draws a tqdm bar of the points (the ``progress`` extra; a widget in a
    notebook with ipywidgets), ``None`` (the default) does so only in a Jupyter notebook
    with tqdm installed, ``False`` never. ``executor``: otherwise a
    ``concurrent.futures.Executor`` or a ``dask.distributed.Client`` (any deployment:
    ``LocalCluster``, ``dask_jobqueue.SLURMCluster``, ...): the points go out as tasks of
    ``chunk_size`` points and come back in grid order. The results are bit-identical to a
    local run. On a Dask client, the memory each point needs (:func:`memory_estimate`,
    given by ``solid_2d`` scenarios) is checked against every worker's ``memory_limit``
    (shared by its threads) before anything is submitted: ``ValueError`` naming the point,
    its estimate and the worker otherwise.

    Returns a pandas DataFrame if pandas is importable (the ``pandas`` extra: ``pip
    install "contactwave[pandas]"``; ``as_frame=False``, or no pandas: a dict of numpy
    arrays; ``as_frame=True`` without pandas raises ``ImportError`` naming the extra): ``point`` (grid index), one column per axis, then the summary keys of
    ``sweep.csv`` (``xi``, ``A1_over_Ainc``, ...). A point whose simulation fails has NaN
    values; a warning names the failed points, and the DataFrame's
    ``attrs["errors"]`` maps them to their messages. The summary columns are those of
    the points that succeeded: when every point fails there are none (only ``point`` and
    the axes). Locally the points run 4096 at a time: memory is the result table plus
    one chunk, whatever the number of points. ``attrs["hash"]`` is the sweep's
    hash, the one ``contactwave sweep`` writes to ``sweep.csv.hash`` for the same base
    scenario and axis values; ``attrs["axes"]`` lists the axes (the keys of ``axes``).
    """
    base_json, base_path = _base(base)
    ax = _axes(axes)
    parameters = [k for k, _ in ax]
    if progress is None or isinstance(progress, bool):
        from ._progress import sweep_bar

        progress = sweep_bar(progress)
    if executor is None:
        points, sweep_hash, (keys, values, errors) = _core.sweep_local(
            base_json, base_path, ax, threads, progress
        )
    else:
        if int(chunk_size) < 1:
            raise ValueError(f"chunk_size: {chunk_size}: must be >= 1")
        points, sweep_hash, memory = _core.sweep_plan(base_json, base_path, ax)
        if _is_dask_client(executor):
            _check_worker_memory(executor, memory, points, parameters)
        parts = _run_on_executor(
            executor, base_json, base_path, parameters, points, int(chunk_size), progress
        )
        keys, values, errors = _join(parts, len(points), int(chunk_size))
    columns: Dict[str, np.ndarray] = {"point": np.arange(len(points), dtype=np.int64)}
    for k, name in enumerate(parameters):
        columns[name] = np.ascontiguousarray(points[:, k])
    for k, name in enumerate(keys):
        if name not in columns:
            columns[name] = np.ascontiguousarray(values[:, k])
    errs = {int(i): str(m) for i, m in errors}
    if errs:
        first = sorted(errs)[:3]
        warnings.warn(
            f"{len(errs)} of {len(points)} sweep points failed (values NaN); first: "
            + "; ".join(f"point {i}: {errs[i]}" for i in first),
            RuntimeWarning,
            stacklevel=2,
        )
    flag = columns.get("harmonic_floor_warning")
    if flag is not None and np.any(flag == 1.0):
        warnings.warn(
            f"{int(np.sum(flag == 1.0))} of {len(points)} sweep points have a harmonic within a "
            "factor 10 of its analysis floor (column harmonic_floor_warning); pulse_inversion "
            "or linear_reference remove the leakage floor",
            HarmonicFloorWarning,
            stacklevel=2,
        )
    if as_frame is None or as_frame:
        try:
            import pandas as pd
        except ImportError as e:
            if as_frame:
                raise ImportError(
                    "cw.sweep(as_frame=True) needs pandas, which `pip install .` does not "
                    "install: pip install \"contactwave[pandas]\" (or `pip install "
                    "\".[pandas]\"` in the repository), or pass as_frame=False for a dict "
                    "of numpy arrays"
                ) from e
        else:
            df = pd.DataFrame(columns)
            df.attrs["errors"] = errs
            df.attrs["hash"] = sweep_hash
            df.attrs["axes"] = parameters
            return df
    return columns


def _join(
    parts: List[Tuple[List[str], np.ndarray, List[Tuple[int, str]]]], n: int, chunk: int
) -> Tuple[List[str], np.ndarray, List[Tuple[int, str]]]:
    """Chunk tables -> one table in grid order (keys: first chunk's, then new ones)."""
    keys: List[str] = []
    for k, _v, _e in parts:
        for name in k:
            if name not in keys:
                keys.append(name)
    values = np.full((n, len(keys)), np.nan)
    errors: List[Tuple[int, str]] = []
    for c, (k, v, e) in enumerate(parts):
        row0 = c * chunk
        if len(k):
            idx = [keys.index(name) for name in k]
            values[row0 : row0 + v.shape[0], idx] = v
        errors.extend((row0 + int(i), m) for i, m in e)
    return keys, values, errors


def plot_sweep(
    table: Any,
    y: str,
    x: Optional[str] = None,
    ax: Any = None,
    *,
    axes: Optional[Sequence[str]] = None,
) -> Any:
    """Plot a summary column ``y`` of a :func:`sweep` table (its DataFrame or dict of
    arrays) against the swept column ``x`` (default: the first axis), one curve per
    value of the other axes (known from the DataFrame's ``attrs["axes"]``, or ``axes``),
    into ``ax`` (a new figure when ``None``); labels with names and SI units. Returns the
    matplotlib Axes; needs the ``plot`` extra."""
    from ._plot import sweep as draw

    return draw(table, y, x, ax, axes)
