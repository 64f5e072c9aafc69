"""``cw.sweep(progress=True)``: a tqdm bar that counts the sweep's points, locally and on
an executor; no bar outside a notebook by default; ImportError naming the extra."""

import concurrent.futures as cf
import sys

import numpy as np
import pytest

import contactwave as cw
from contactwave import _progress
from conftest import CHEAP

tqdm_std = pytest.importorskip("tqdm.std")


@pytest.fixture
def bars(monkeypatch):
    """The bars the sweep draws (a recording tqdm subclass, silent)."""
    made = []

    class Recording(tqdm_std.tqdm):
        def __init__(self, *args, **kwargs):
            kwargs["disable"] = False
            kwargs["file"] = open("/dev/null", "w")  # noqa: SIM115 - closed with the bar
            super().__init__(*args, **kwargs)
            self.updates = []
            made.append(self)

        def update(self, n=1):
            self.updates.append(n)
            return super().update(n)

    monkeypatch.setattr(_progress, "bar_class", lambda: Recording)
    return made


def test_the_bar_counts_every_point_of_a_local_sweep(bars):
    xi = np.linspace(0.05, 1.2, 37)
    df = cw.sweep(CHEAP, {"incident.xi": xi, "interface.static_pressure": [0.1e6, 0.2e6]},
                  progress=True, as_frame=False)
    assert len(df["point"]) == 74
    (bar,) = bars
    assert bar.total == 74 and bar.n == 74 and sum(bar.updates) == 74
    assert all(u > 0 for u in bar.updates)
    assert bar.disable  # closed (tqdm marks a closed bar disabled)


def test_the_bar_counts_the_chunks_of_an_executor_sweep(bars):
    xi = np.linspace(0.05, 1.2, 10)
    with cf.ThreadPoolExecutor(2) as ex:
        cw.sweep(CHEAP, {"incident.xi": xi}, executor=ex, chunk_size=3, progress=True,
                 as_frame=False)
    (bar,) = bars
    assert bar.total == 10 and bar.n == 10
    assert bar.updates == [3, 3, 3, 1]  # one update per chunk, in grid order


def test_no_bar_by_default_outside_a_notebook(bars):
    cw.sweep(CHEAP, {"incident.xi": [0.1, 0.2]}, as_frame=False)
    cw.sweep(CHEAP, {"incident.xi": [0.1, 0.2]}, as_frame=False, progress=False)
    assert bars == [] and not _progress.in_notebook()


def test_progress_true_without_tqdm_names_the_extra(monkeypatch):
    monkeypatch.setitem(sys.modules, "tqdm", None)
    with pytest.raises(ImportError, match=r"contactwave\[progress\]"):
        cw.sweep(CHEAP, {"incident.xi": [0.1]}, progress=True)


def test_the_bar_counts_the_points_of_a_dask_sweep(bars):
    distributed = pytest.importorskip("dask.distributed")
    xi = np.linspace(0.05, 1.2, 25)
    with distributed.LocalCluster(
        n_workers=1, threads_per_worker=2, processes=False, dashboard_address=None
    ) as cluster, distributed.Client(cluster) as client:
        d = cw.sweep(CHEAP, {"incident.xi": xi}, executor=client, chunk_size=10,
                     progress=True, as_frame=False)
    assert len(d["point"]) == 25
    (bar,) = bars
    assert bar.total == 25 and bar.n == 25 and bar.updates == [10, 10, 5]
