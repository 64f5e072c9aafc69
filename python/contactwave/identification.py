"""``contactwave.identify`` and its result :class:`Identification` (docs/identify.md)."""

from __future__ import annotations

import json
import os
import warnings
from typing import Any, Dict, List, Mapping, Optional, Union

import numpy as np

from . import _core
from ._core import SimulationError


class Identification(dict):
    """The result of :func:`identify`: the ``identification.json`` object (a dict:
    ``estimates``, ``intervals``, ``verdicts``, ``residual_norm``, ...), plus the
    measured and fitted values per data row, the columns of ``fit.csv``: ``fit_table``
    (dict of float arrays: the conditions, e.g. ``incident.xi``, then per observed key
    ``<key>``, ``fitted_<key>`` and ``sigma_<key>``), ``conditions`` (the condition
    columns, the control variable first) and ``observed`` (the observed keys). A design
    ranking (``design=True``) has an empty ``fit_table``."""

    def __init__(
        self,
        result: Mapping[str, Any],
        fit_csv: str = "",
        fit_table: Optional[Dict[str, np.ndarray]] = None,
    ) -> None:
        super().__init__(result)
        from ._plot import parse_fit_csv

        self.fit_table: Dict[str, np.ndarray] = (
            parse_fit_csv(fit_csv) if fit_table is None else dict(fit_table)
        )
        cols = list(self.fit_table)
        self.observed: List[str] = [c[len("fitted_"):] for c in cols if c.startswith("fitted_")]
        derived = {f"{p}_{k}" for k in self.observed for p in ("fitted", "sigma")}
        self.conditions: List[str] = [
            c for c in cols if c not in derived and c not in self.observed
        ]

    def plot(self, observed: Optional[str] = None, ax: Any = None) -> Any:
        """The measured values (points with 1-sigma bars) and the fitted model (line) of
        the observed key ``observed`` (default the first) against the control variable,
        one curve per value of the further conditions; into ``ax`` (a new figure when
        ``None``). Returns the matplotlib Axes; needs the ``plot`` extra."""
        from ._plot import identification

        return identification(self, observed, ax)

    def __reduce__(self) -> Any:
        return (Identification, (dict(self), "", self.fit_table))


def _plain(value: Any, key: str, file: str) -> Any:
    from . import _plain as plain

    return plain(value, key, file)


def identify(
    spec: Union[str, "os.PathLike[str]", Mapping[str, Any]],
    out: Optional[Union[str, "os.PathLike[str]"]] = None,
    design: bool = False,
    file: str = "<dict>",
    *,
    tolerate_failures: bool = False,
) -> "Identification":
    """Identify interface parameters from a measured curve (``contactwave identify``; see
    docs/identify.md).

    ``spec`` is the path of an identification file (TOML) or a dict with its keys
    (``base``, ``data``: a CSV path or a dict of equally long columns, or instead
    ``records``: raw waveforms reduced like the forward signals, docs/identify.md section 8,
    ``observed``,
    ``set``, ``parameter``: a list of dicts with ``key``, ``bounds``, ``scale``, ...,
    ``fit``, ``design``); a dict's relative paths resolve against the folder of ``file``
    (``<dict>``: the working directory). Returns the ``identification.json`` object:
    ``estimates`` (key -> value, SI), ``intervals`` (key -> [low, high], ``None`` bounds
    for a non-identifiable parameter), ``verdicts``, ``residual_norm``, ``forward_runs``,
    ``wall_seconds``, ``jacobian_svd``, ... With ``design=True``, the ranking of the
    ``[design]`` candidates (``design.json``) instead. With ``out``, the output files are
    written into that folder. The GIL is released while it runs. Raises ``ValueError``
    naming the file, field, value and allowed range for invalid input.

    The result is an :class:`Identification`: the ``identification.json`` dict, with the
    measured and fitted values of ``fit.csv`` as ``fit_table`` and a :meth:`plot
    <Identification.plot>` of them.

    Forward runs that fail (numerically, or with a non-finite observed value) get a
    prohibitive cost and the fit goes on; the result then carries
    ``failed_forward_runs`` and ``first_failure``, and, unless ``tolerate_failures``,
    :class:`SimulationError` is raised (after the files are written), as the CLI exits 1
    without ``--tolerate-failures``.
    """
    out_path = None if out is None else os.fspath(out)
    if isinstance(spec, Mapping):
        text = json.dumps(_plain(spec, "", file))
        res = _core.identify(text, file, out_path, design)
    else:
        res = _core.identify(None, os.fspath(spec), out_path, design)
    text, fit_csv = res
    result = json.loads(text)
    if isinstance(result, dict):
        result = Identification(result, fit_csv)
    failed = result.get("failed_forward_runs", 0) if isinstance(result, dict) else 0
    if failed:
        msg = (
            f"{failed} of {result.get('forward_runs')} forward runs failed (the fit gave "
            f"them a prohibitive cost); first: {result.get('first_failure')}"
        )
        if not tolerate_failures:
            raise SimulationError(msg + " (tolerate_failures=True to accept)")
        warnings.warn(msg, RuntimeWarning, stacklevel=2)
    return result
