"""A sweep spread over a ``dask.distributed`` cluster (docs/python.md): the plans are cut into shares of
consecutive indices, each worker plans its shares with ``mintorque.sweep_table(..., share=(start, end))``
(on all its cores, warm starts within the share), and the rows are gathered into one table — the same
table, row for row, that ``mintorque.sweep`` writes on one machine.

    from dask.distributed import Client
    import mintorque.dask
    client = Client("tcp://scheduler:8786")          # or Client(LocalCluster(n_workers=2))
    table = mintorque.dask.sweep("sweep.toml", "out/sweep", client)

The sweep file, its base task and the models must be readable at the same paths on every worker (a
shared file system), and every worker needs the mintorque package. Each share keeps its own resumable
table in ``OUT/shares/START-END/``: a share that fails or is lost is planned again by re-running.
"""

from __future__ import annotations

import csv
import io
import os
from typing import Any, List, Optional, Tuple, Union

from . import _columns
from ._mintorque import sweep_size, sweep_table


def _plan_share(path: str, out: str, share: Tuple[int, int], keep_plans: bool, warm_starts: bool) -> str:
    """On a worker: plans one share and returns its table's text (header first)."""
    table = sweep_table(path, out, keep_plans, warm_starts, share)
    with open(table, newline="") as f:
        return f.read()


def shares(total: int, count: int) -> List[Tuple[int, int]]:
    """``count`` runs of consecutive indices covering ``0..total`` (as equal as they can be)."""
    count = max(1, min(count, total))
    bounds = [round(k * total / count) for k in range(count + 1)]
    return [(bounds[k], bounds[k + 1]) for k in range(count) if bounds[k] < bounds[k + 1]]


def sweep(path: Union[str, os.PathLike], out: Union[str, os.PathLike], client: Any, share_count: Optional[int] = None,
          keep_plans: bool = False, warm_starts: bool = True) -> Any:
    """Plans the sweep file ``path`` on the workers of ``client`` and writes the gathered table to
    ``out/sweep.csv``; returns it as ``mintorque.sweep`` does (a DataFrame with pandas, else columns).
    ``share_count`` defaults to four shares per worker thread."""
    path, out = os.path.abspath(os.fspath(path)), os.path.abspath(os.fspath(out))
    total = sweep_size(path)
    threads = sum(client.nthreads().values()) or 1
    runs = shares(total, share_count or 4 * threads)
    futures = [
        client.submit(_plan_share, path, os.path.join(out, "shares", f"{a}-{b}"), (a, b), keep_plans, warm_starts,
                      pure=False)
        for a, b in runs
    ]
    texts = client.gather(futures)
    header: Optional[List[str]] = None
    rows: List[List[str]] = []
    for text in texts:
        reader = csv.reader(io.StringIO(text))
        header = next(reader)
        rows.extend(reader)
    rows.sort(key=lambda r: int(r[0]))
    os.makedirs(out, exist_ok=True)
    table = os.path.join(out, "sweep.csv")
    with open(table, "w", newline="") as f:
        writer = csv.writer(f, lineterminator="\n")
        writer.writerow(header or [])
        writer.writerows(rows)
    try:
        import pandas
    except ImportError:
        return _columns(table)
    return pandas.read_csv(table, keep_default_na=False, na_values=["NaN"])
