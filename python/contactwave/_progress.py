"""Progress bars of :func:`contactwave.sweep` (tqdm, the ``progress`` extra).

``progress=True`` draws a tqdm bar (a widget in a Jupyter notebook with ipywidgets, text on
stderr otherwise); ``progress=None`` does so only in a Jupyter kernel with tqdm installed;
``progress=False`` never. The bar counts the sweep's points as the library reports them
(locally at most every 50 ms and once at the end; with an executor as the chunks come back).
"""

from __future__ import annotations

from typing import Any, Optional

from ._frames import require


def in_notebook() -> bool:
    """True in a Jupyter kernel (IPython's ``IPKernelApp``), the notebooks' case."""
    try:
        from IPython import get_ipython  # type: ignore[attr-defined]
    except ImportError:
        return False
    shell = get_ipython()
    return shell is not None and "IPKernelApp" in getattr(shell, "config", {})


def bar_class() -> Any:
    """The tqdm class to draw with: the notebook widget in a kernel with ipywidgets, the
    text bar otherwise (tqdm.auto would warn without ipywidgets)."""
    require("tqdm", "progress", "cw.sweep(progress=True)")
    if in_notebook():
        try:
            import ipywidgets  # noqa: F401

            from tqdm.notebook import tqdm as bar

            return bar
        except ImportError:
            pass
    from tqdm.std import tqdm as bar

    return bar


class SweepBar:
    """A ``progress(done, total)`` callback that moves a tqdm bar to ``done`` of
    ``total`` points and closes it at ``total``."""

    def __init__(self) -> None:
        self.bar: Any = None

    def __call__(self, done: int, total: int) -> None:
        if self.bar is None:
            self.bar = bar_class()(total=int(total), desc="sweep", unit="point")
        if done > self.bar.n:
            self.bar.update(int(done) - self.bar.n)
        if done >= total:
            self.close()

    def close(self) -> None:
        if self.bar is not None and not getattr(self.bar, "disable", False):
            self.bar.close()


def sweep_bar(progress: Optional[bool]) -> Optional[SweepBar]:
    """The bar of ``cw.sweep(progress=...)`` for ``True``, ``False`` or ``None`` (auto:
    in a notebook, when tqdm is installed)."""
    if progress is False:
        return None
    if progress is None:
        if not in_notebook():
            return None
        try:
            import tqdm  # noqa: F401
        except ImportError:
            return None
    else:
        bar_class()  # ImportError naming the extra now, before the sweep runs
    return SweepBar()
