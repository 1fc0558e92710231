"""Type stubs of the mintorque package (docs/python.md). Arrays are float64, SI units."""

import os
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

__version__: str

Array = npt.NDArray[np.float64]
ArrayLike = npt.ArrayLike
PathLike = Union[str, os.PathLike]

class MintorqueError(ValueError):
    """Bad input (the message names the file and field) or a failed plan."""

class Model:
    """A figure and its dynamics. Every algorithm takes one state (1-D arrays of ``nv``) or a batch
    (2-D, ``n × nv``) and returns the same batch shape."""
    @staticmethod
    def load(path: PathLike) -> "Model":
        """Reads a URDF (``.urdf``) or figure file (``.toml``)."""
    @staticmethod
    def human(structure: str = "sagittal", stature: float = 1.83, mass: float = 81.0) -> "Model":
        """A built-in human (sagittal, free_arms, hanging, push_up), scaled to stature (m) and mass (kg)."""
    @property
    def nv(self) -> int: ...
    @property
    def joint_names(self) -> List[str]: ...
    @property
    def name(self) -> str: ...
    def rnea(self, q: ArrayLike, v: ArrayLike, a: ArrayLike, gravity: Optional[Sequence[float]] = None) -> Array:
        """Inverse dynamics τ (N·m or N); gravity in m/s², default the model's."""
    def rnea_derivatives(
        self, q: ArrayLike, v: ArrayLike, a: ArrayLike, gravity: Optional[Sequence[float]] = None
    ) -> Tuple[Array, Array, Array]:
        """(∂τ/∂q, ∂τ/∂q̇, H), each nv × nv per state."""
    def crba(self, q: ArrayLike) -> Array:
        """The joint-space inertia matrix H(q), nv × nv per state."""
    def aba(self, q: ArrayLike, v: ArrayLike, tau: ArrayLike, gravity: Optional[Sequence[float]] = None) -> Array:
        """Forward dynamics q̈ (rad/s² or m/s²)."""

class PlanResult:
    """A planned motion, sampled at the task's output rate."""
    t: Array
    q: Array
    qd: Array
    qdd: Array
    tau: Array
    contact_forces: Array
    joint_names: List[str]
    converged: bool
    reason: str
    effort: float
    iterations: int
    solve_seconds: float
    @property
    def summary(self) -> Dict[str, Any]:
        """summary.json of the plan."""

def plan(
    task: Union[PathLike, Dict[str, Any]],
    solver: Optional[str] = None,
    starts: Union[int, str, None] = None,
    control_points: Optional[int] = None,
) -> PlanResult:
    """Plans a task file (path) or a dict with its structure; the GIL is released while it solves."""

def sweep(path: PathLike, out: PathLike, keep_plans: bool = False, warm_starts: bool = True) -> Any:
    """Runs a sweep file into ``out`` and returns its table (a pandas DataFrame when pandas is installed,
    else a dict of columns)."""

def sweep_table(
    path: PathLike, out: PathLike, keep_plans: bool = False, warm_starts: bool = True, share: Optional[Tuple[int, int]] = None
) -> str:
    """Runs a sweep (only the plans with an index in ``share``'s range, when given) and returns its CSV path."""

def sweep_size(path: PathLike) -> int:
    """The number of plans of a sweep file."""
