"""The Dask helper on a LocalCluster of two worker processes: the gathered table equals, row for row, the
table of the same sweep on one machine."""

import os

import pytest

import mintorque
import mintorque.dask

from dask import distributed  # installed by scripts/python-test.sh: the test fails, never skips, without it

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))


def test_shares_cover_every_index_once():
    assert mintorque.dask.shares(10, 4) == [(0, 2), (2, 5), (5, 8), (8, 10)]
    assert mintorque.dask.shares(3, 8) == [(0, 1), (1, 2), (2, 3)]


def test_a_sweep_on_two_workers_equals_the_local_sweep(tmp_path):
    sweep_file = tmp_path / "sweep.toml"
    sweep_file.write_text(
        f'base = "{os.path.join(ROOT, "examples", "pendulum.toml")}"\n'
        '[[parameter]]\npath = "environment.gravity"\nvalues = ["earth", "mars"]\n'
        '[[parameter]]\npath = "motion.duration"\nrange = { from = 0.5, to = 0.7, step = 0.05 }\n'
    )
    # Cold starts everywhere: the result of each plan then does not depend on which plans share a worker.
    local = mintorque.sweep(sweep_file, tmp_path / "local", warm_starts=False)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with distributed.Client(cluster) as client:
            spread = mintorque.dask.sweep(sweep_file, tmp_path / "spread", client, warm_starts=False)
    assert list(spread["index"]) == list(range(10))
    assert list(spread["status"]) == list(local["status"]) == ["converged"] * 10
    for a, b in zip(spread["effort"], local["effort"]):
        assert a == pytest.approx(b, rel=1e-12)
    assert os.path.isdir(tmp_path / "spread" / "shares")
