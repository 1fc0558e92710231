"""mintorque — minimum-joint-torque motion planning for articulated figures (Lo, Huang & Metaxas 2001).

The Python face of the Rust library (docs/python.md)::

    import mintorque
    jack = mintorque.Model.human("sagittal", stature=1.83, mass=81.0)
    tau = jack.rnea(q, v, a)                     # one state (nv,) or a batch (n, nv)
    result = mintorque.plan("examples/arm_lift_earth.toml")
    result.tau                                   # samples × nv, N·m
    table = mintorque.sweep("examples/sweeps/arm_lift.toml", "out/sweep")   # a pandas DataFrame

Units are SI (m, kg, s, rad, N, N·m) in every array; task files write angles in degrees. Errors are
``MintorqueError`` (a ``ValueError``) with the file/field message.
"""

from __future__ import annotations

import csv
import os
from typing import Any, Dict, List, Union

from ._mintorque import MintorqueError, Model, PlanResult, __version__, plan, sweep_table

__all__ = ["Model", "PlanResult", "MintorqueError", "plan", "sweep", "__version__"]


def sweep(path: Union[str, os.PathLike], out: Union[str, os.PathLike], keep_plans: bool = False,
          warm_starts: bool = True) -> Any:
    """Runs the sweep file ``path`` into the directory ``out`` (docs/sweeps.md) and returns its table,
    one row per plan sorted by ``index``: a pandas DataFrame when pandas is installed, else a dict of
    column name → list. Re-running resumes (the plans already in ``out/sweep.csv`` are skipped)."""
    table = sweep_table(os.fspath(path), os.fspath(out), keep_plans, warm_starts)
    try:
        import pandas
    except ImportError:
        return _columns(table)
    return pandas.read_csv(table, keep_default_na=False, na_values=["NaN"]).sort_values("index").reset_index(drop=True)


def _columns(table: str) -> Dict[str, List[Any]]:
    with open(table, newline="") as f:
        rows = sorted(csv.DictReader(f), key=lambda r: int(r["index"]))
    columns: Dict[str, List[Any]] = {k: [] for k in (rows[0].keys() if rows else [])}
    for r in rows:
        for k, v in r.items():
            try:
                columns[k].append(int(v) if k in ("index", "iterations") else float(v))
            except ValueError:
                columns[k].append(v)
    return columns
