"""2D sweeps at scale (issue 27): the 50-point crack-length sweep of the quick reference
case on a Dask LocalCluster gives the rows of `contactwave sweep` bit for bit, and a sweep
whose points would not fit a worker's memory is refused before anything is submitted."""

import numpy as np
import pytest

import contactwave as cw
from conftest import run_cli
from test_sweep import assert_bits_equal, cli_table

SWEEP = "examples/sweeps/crack_length_quick.toml"
BASE = "examples/solid_2d/plate_crack_quick.toml"


def test_dask_crack_length_sweep_gives_the_cli_rows(cli, root, tmp_path):
    distributed = pytest.importorskip("dask.distributed")
    run_cli(cli, "sweep", root / SWEEP, "--out", tmp_path / "out")
    ref = cli_table(tmp_path / "out" / "sweep.csv")
    assert len(ref) == 50
    # the axis values as the CLI computed them (its linspace), read back exactly
    lengths = ref["crack.0.length"].to_numpy()
    assert lengths[0] == 0.5e-3 and lengths[-1] == 20e-3
    axes = {"crack.0.length": lengths}
    memory = cw.memory_estimate(root / BASE, axes)
    assert memory.shape == (50,) and np.all(np.isfinite(memory))
    # a longer crack adds crack nodes and their records (and the mesh lines at its end
    # may shorten the time step)
    assert 1e6 < memory.min() and memory.max() < 1e8 and memory[0] < memory[-1]
    with distributed.LocalCluster(
        n_workers=2,
        threads_per_worker=1,
        processes=True,
        memory_limit="2GB",
        dashboard_address=None,
    ) as cluster, distributed.Client(cluster) as client:
        df = cw.sweep(root / BASE, axes, executor=client, chunk_size=5)
    assert df.attrs["errors"] == {}
    assert df.attrs["hash"] == (tmp_path / "out" / "sweep.csv.hash").read_text().strip()
    assert_bits_equal(df, ref)
    # the physics the rows carry: the 0.5 mm crack opens less than the 20 mm one, and
    # every crack claps (A2/A1 at the bottom receiver of at least a few percent)
    gap = df["crack_max_gap_0"].to_numpy()
    assert gap[0] < gap[-1] and np.all(gap > 0)
    assert np.all(df["bottom_A2_over_A1"].to_numpy() > 0.02)


def test_a_sweep_beyond_a_workers_memory_is_refused_before_submitting(root):
    distributed = pytest.importorskip("dask.distributed")
    # the quick case on a mesh of 37.5 um elements (order 6): about 1e7 nodes, estimated
    # without building them (the mesh, the records and the files they make)
    axes = {"model.element_size": [0.2e-3, 37.5e-6]}
    memory = cw.memory_estimate(root / BASE, axes)
    assert 0.5e9 < memory[1] < 2e9 and memory[0] < memory[1] / 10
    with distributed.LocalCluster(
        n_workers=1,
        threads_per_worker=2,
        processes=True,
        memory_limit="1GB",
        dashboard_address=None,
    ) as cluster, distributed.Client(cluster) as client:
        with pytest.raises(ValueError) as e:
            cw.sweep(root / BASE, axes, executor=client)
        # nothing ran on the cluster
        assert client.run(lambda dask_worker: len(dask_worker.data)) == {
            a: 0 for a in client.scheduler_info()["workers"]
        }
    msg = str(e.value)
    assert "sweep point 1" in msg and "model.element_size = 3.75e-05" in msg
    assert "2 task(s) at once" in msg and "memory_limit of 1000 MB" in msg


def test_a_task_checks_its_share_of_the_workers_memory_before_it_starts(root):
    """A task sent without the client's check (any executor) still refuses a point whose
    estimate exceeds its share of the worker's memory_limit, before building it: the point
    fails with the message, nothing is allocated."""
    distributed = pytest.importorskip("dask.distributed")
    base_json, base_path = cw._base(root / BASE)
    points = np.array([[0.78e-3], [25e-6]])
    with distributed.LocalCluster(
        n_workers=1,
        threads_per_worker=2,
        processes=True,
        memory_limit="1GB",
        dashboard_address=None,
    ) as cluster, distributed.Client(cluster) as client:
        keys, values, errors = client.submit(
            cw._run_chunk, base_json, base_path, ["model.element_size"], points, pure=False
        ).result()
    # the coarse point ran, the fine one (about 1.6 GB, above 1 GB / 2 threads) did not
    assert [i for i, _ in errors] == [1]
    msg = errors[0][1]
    assert "model.element_size" in msg and "memory budget of 500 MB" in msg, msg
    assert values.shape[0] == 2 and np.isfinite(values[0, keys.index("bottom_A2_over_A1")])
