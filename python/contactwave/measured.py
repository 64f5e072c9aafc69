"""Measured records through the simulator's own harmonic analysis: ``analyze`` and its
result ``Analysis`` (docs/model.md section 16, docs/python.md)."""
from __future__ import annotations

import json
import os
import warnings
from typing import Any, Dict, List, Mapping, Optional, Sequence

import numpy as np

from . import _core


class Analysis:
    """The analysis of measured records by ``contactwave.analyze`` (docs/model.md section
    16): ``summary`` (the dict of ``summary.json``), ``f0`` (Hz), ``f0_detected``,
    ``method``, ``records`` (a list of dicts with ``name``, ``amplitude``, ``A1`` ... ``A5``,
    ``A2_over_A1``, ``A3_over_A1``, ``beta_star``, ``A2_floor`` ... ``A5_floor``,
    ``harmonic_floor_warning``), ``fit`` (the fit of A2 against A1^2 over a series, or
    ``None``), and numpy arrays ``A`` (records x 5: A1..A5), ``beta_star``,
    ``A2_over_A1``.

    The record the CLI's pictures show (the largest A1, index ``record``): ``t`` (s), ``raw``
    (as read, its mean removed), ``gated`` (through the gate), and the gated record's
    spectrum ``frequency`` (Hz, up to 6 f0) and ``magnitude`` (``|X(f)| dt``: the record's
    unit times s), the columns of ``spectrum.csv``; :meth:`plot` draws them."""

    def __init__(self, summary: Mapping[str, Any], picture: Optional[Sequence[Any]] = None) -> None:
        self.summary: Dict[str, Any] = dict(summary)
        self.f0: float = summary["f0"]
        self.f0_detected: bool = summary["f0_detected"]
        self.method: str = summary["method"]
        self.records: List[Dict[str, Any]] = list(summary["records"])
        self.fit: Optional[Dict[str, Any]] = summary.get("fit")

        def col(k: str) -> np.ndarray:
            return np.array([np.nan if r.get(k) is None else r[k] for r in self.records], dtype=np.float64)

        self.A: np.ndarray = np.stack([col(f"A{n}") for n in range(1, 6)], axis=1)
        self.A2_over_A1: np.ndarray = col("A2_over_A1")
        self.beta_star: np.ndarray = col("beta_star")
        self.warnings: List[str] = list(summary.get("warnings", []))
        empty = np.zeros(0)
        record, t, raw, gated, frequency, magnitude = (
            picture if picture is not None else (0, empty, empty, empty, empty, empty)
        )
        self.record: int = int(record)
        self.t: np.ndarray = t
        self.raw: np.ndarray = raw
        self.gated: np.ndarray = gated
        self.frequency: np.ndarray = frequency
        self.magnitude: np.ndarray = magnitude

    def plot(self, kind: str = "spectrum", ax: Any = None) -> Any:
        """One matplotlib panel (needs the ``plot`` extra), drawn into ``ax`` (a new
        figure when ``None``); returns the Axes. ``kind``: ``"record"`` (the record ``t``,
        ``raw`` and ``gated``, s; the gate's edges dashed), ``"spectrum"`` (``frequency``,
        ``magnitude`` on a log scale, dotted markers at n f0), ``"harmonics"`` (A1...A5 of
        the record against n, with its floors ``A<n>_floor``, ``A<n>_noise_floor``,
        ``A<n>_leakage_floor``), ``"fit"`` (A2 against A1^2 over the series, with the fitted
        line; needs a series)."""
        from ._plot import analysis

        return analysis(self, kind, ax)

    def to_pandas(self) -> Any:
        """The records as a pandas DataFrame (one row per record; needs pandas)."""
        try:
            import pandas as pd
        except ImportError as e:  # pragma: no cover - depends on the environment
            raise ImportError("Analysis.to_pandas needs pandas: pip install 'contactwave[pandas]'") from e
        return pd.DataFrame(self.records)

    def __repr__(self) -> str:
        return f"Analysis(f0={self.f0:.6g} Hz, method={self.method!r}, records={len(self.records)})"


def analyze(
    records: Any,
    *,
    dt: Optional[float] = None,
    sample_rate: Optional[float] = None,
    t0: float = 0.0,
    f0: Optional[float] = None,
    gate: Optional[Sequence[float]] = None,
    method: str = "band_peak",
    inverse: Any = None,
    linear: Any = None,
    amplitudes: Any = None,
    keep_dc: bool = False,
    time: Optional[str] = None,
    datasets: Optional[Sequence[str]] = None,
    full_scale: Optional[float] = None,
) -> Analysis:
    """Measured records through the simulator's own harmonic analysis (the CLI's
    ``contactwave analyze``; docs/model.md section 16).

    ``records``: a numpy array (one record, or samples x records), a list of 1-D arrays,
    or a file path / list of paths (CSV, ``.npy``, ``.npz``, ``.mat`` v5 or v7.3, HDF5).
    Arrays need ``dt`` (s) or ``sample_rate`` (Hz) and optionally ``t0`` (s); files carry
    their time base (a column or array ``t``/``time``, or give ``sample_rate``), and
    ``datasets`` / ``time`` name their arrays. ``f0`` (Hz, default detected), ``gate``
    ``(start, end[, taper])`` in s, ``method`` (``band_peak``, ``pulse_inversion`` with
    ``inverse``, ``linear_reference`` with ``linear``, ``plateau_fit`` with a gate),
    ``amplitudes`` (one per record, or the name of an array of the first file),
    ``full_scale`` (the digitiser's full scale in the records' unit: samples at it are
    clipped; default: clipping detected as flat runs at a record's extremes). A clipped
    record has ``clipped_samples > 0`` and ``harmonics_reliable == 0`` and warns. An array
    whose first column increases in uniform steps (a time axis) is refused.
    Invalid input raises ``ValueError`` naming the file, field and allowed values."""
    opts: Dict[str, Any] = {"method": method, "keep_dc": bool(keep_dc), "t0": float(t0)}
    if f0 is not None:
        opts["f0"] = float(f0)
    if gate is not None:
        opts["gate"] = [float(g) for g in gate]
    if full_scale is not None:
        opts["full_scale"] = float(full_scale)
    if amplitudes is not None:
        opts["amplitudes"] = amplitudes if isinstance(amplitudes, str) else [float(a) for a in np.ravel(amplitudes)]

    def is_path(x: Any) -> bool:
        return isinstance(x, (str, os.PathLike))

    def arrays(x: Any) -> List[np.ndarray]:
        if x is None:
            return []
        if isinstance(x, (list, tuple)) and x and not np.isscalar(x[0]):
            return [np.ascontiguousarray(np.asarray(r, dtype=np.float64).ravel()) for r in x]
        a = np.asarray(x)
        if np.iscomplexobj(a):
            raise ValueError("records: complex data; pass the real part")
        a = a.astype(np.float64)
        if a.ndim == 1:
            return [np.ascontiguousarray(a)]
        if a.ndim == 2:
            cols = a if a.shape[0] < a.shape[1] else a.T
            first = cols[0]
            steps = np.diff(first)
            if len(cols) > 1 and first.size >= 16 and np.all(steps > 0) and np.ptp(steps) <= 0.25 * steps.mean():
                raise ValueError(
                    "records: column 0 increases in uniform steps from "
                    f"{first[0]:g} to {first[-1]:g}: a time axis, not a record; pass the "
                    "records alone with dt (or sample_rate), or the file, whose time column is read"
                )
            return [np.ascontiguousarray(c) for c in cols]
        raise ValueError(f"records: an array of {a.ndim} dimensions; one record, or samples x records")

    paths = [records] if is_path(records) else (list(records) if isinstance(records, (list, tuple)) and records and all(is_path(r) for r in records) else None)
    if paths is not None:
        if dt is not None:
            raise ValueError("dt: files carry their time base (a time column, or sample_rate for a file without one)")
        opts["files"] = [os.fspath(p) for p in paths]
        if sample_rate is not None:
            opts["sample_rate"] = float(sample_rate)
        if time is not None:
            opts["time"] = time
        if datasets is not None:
            opts["datasets"] = list(datasets)
        if inverse is not None:
            opts["inverse_files"] = [os.fspath(p) for p in (inverse if isinstance(inverse, (list, tuple)) else [inverse])]
        if linear is not None:
            opts["linear_file"] = os.fspath(linear)
        out = _core.analyze([], [], [], json.dumps(opts))
    else:
        if dt is None:
            if sample_rate is None:
                raise ValueError("analyze: arrays need dt (s) or sample_rate (Hz)")
            dt = 1.0 / float(sample_rate)
        elif sample_rate is not None and abs(float(dt) * float(sample_rate) - 1.0) > 1e-9:
            raise ValueError(f"dt = {dt} s and sample_rate = {sample_rate} Hz disagree: give one of them")
        opts["dt"] = float(dt)
        out = _core.analyze(arrays(records), arrays(inverse), arrays(linear), json.dumps(opts))
    result = Analysis(json.loads(out[0]), out[1:])
    for w in result.warnings:
        from . import HarmonicFloorWarning

        warnings.warn(w, HarmonicFloorWarning, stacklevel=2)
    return result
