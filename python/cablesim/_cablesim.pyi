"""Type stubs of the extension module cablesim._cablesim (re-exported by cablesim).

Units are SI: m, s, N, kg. Arrays are float64 numpy arrays the caller owns.
"""

import os
from typing import Any, Dict, List, Literal, Optional, Sequence, Union, final, overload

import numpy as np
import numpy.typing as npt

__version__: str
__all__ = [
    "__version__",
    "CablesimError",
    "ScenarioError",
    "DivergedError",
    "GpuError",
    "OutputError",
    "Simulation",
    "Snapshot",
    "BodyState",
    "RunOutput",
    "run_study",
]

_Cable = Union[int, str]
"""A cable by index (scenario order; negative from the last) or name."""
_Body = Union[int, str]
"""A vessel body by index or name."""
_End = Literal["start", "end"]
"""A cable end: its first node ("start") or its last ("end")."""
_Vec3 = Union[Sequence[float], npt.NDArray[np.float64]]
_FloatArray = npt.NDArray[np.float64]

def run_study(
    path: Union[str, os.PathLike[str]],
    out_dir: Union[str, os.PathLike[str]],
    *,
    backend: Optional[Literal["auto", "cpu", "gpu"]] = None,
    precision: Optional[Literal["f32", "f64"]] = None,
    batch: Optional[int] = None,
) -> Dict[str, Any]:
    """Runs every member of the study file ``path`` (a ``[study]`` table), writes
    ``study.csv``, ``members.csv`` and ``study.json`` into ``out_dir`` (and
    ``fatigue.csv`` when the base scenario has a ``[fatigue]`` table) and returns the
    content of ``study.json``. ``backend`` as ``cablesim study run --backend``: "cpu"
    (the default; members across all threads), "gpu" or "auto" (members packed into
    one run, ``batch`` at a time, at ``precision``). Ctrl-C stops it with
    KeyboardInterrupt."""

class CablesimError(Exception):
    """Base class of every error cablesim raises (besides ValueError, KeyError and
    IndexError for a wrong argument)."""

class ScenarioError(CablesimError):
    """A scenario is wrong."""

    path: str
    """The file."""
    field: str
    """The offending field, as a dotted path (``cables[2].length``)."""
    message: str
    """What is wrong with it."""

class DivergedError(CablesimError):
    """The simulation blew up."""

    cable: str
    """The cable's name."""
    node: int
    """Node index within the cable."""
    time: float
    """Simulated time, s."""

class GpuError(CablesimError):
    """No usable GPU adapter, a GPU failure, or something the GPU path does not do."""

class OutputError(CablesimError):
    """Writing an output file failed."""

    path: str
    """The file."""

@final
class Simulation:
    """A scenario being simulated.

    Build one with ``Simulation.from_file(path)`` (a TOML scenario or a MoorDyn input
    file) or ``Simulation.from_toml(text)``; keyword arguments override the scenario's
    ``[simulation]`` settings. Then run it to the end (``run``), or step it
    (``advance``, ``advance_to``) and read its state in between, driving held ends from
    outside (``set_end_motion``) as a coupling loop does. Stepping releases the GIL;
    Ctrl-C raises KeyboardInterrupt between chunks of about a tenth of a second.
    """

    @classmethod
    def from_file(
        cls,
        path: Union[str, os.PathLike[str]],
        *,
        backend: Optional[Literal["auto", "cpu", "gpu"]] = None,
        precision: Optional[Literal["f32", "f64"]] = None,
        scheme: Optional[Literal["symplectic", "rk2", "rk4"]] = None,
        formulation: Optional[Literal["glmf", "rvef", "euler", "frenet", "ancf"]] = None,
        dt: Optional[float] = None,
        duration: Optional[float] = None,
    ) -> "Simulation":
        """Reads a scenario file (TOML, or a MoorDyn input file) and builds its
        simulation. ``dt`` and ``duration`` are in s. Raises ScenarioError naming the
        file and the field, ValueError for an unknown option name."""
    @classmethod
    def from_toml(
        cls,
        text: str,
        *,
        name: Optional[Union[str, os.PathLike[str]]] = None,
        backend: Optional[Literal["auto", "cpu", "gpu"]] = None,
        precision: Optional[Literal["f32", "f64"]] = None,
        scheme: Optional[Literal["symplectic", "rk2", "rk4"]] = None,
        formulation: Optional[Literal["glmf", "rvef", "euler", "frenet", "ancf"]] = None,
        dt: Optional[float] = None,
        duration: Optional[float] = None,
    ) -> "Simulation":
        """Builds the simulation of scenario text (TOML). ``name`` stands for the file in
        messages and the summary (default "scenario.toml"); relative route and motion
        files are read beside it."""
    @property
    def time(self) -> float:
        """Simulated time, s."""
    @property
    def steps(self) -> int:
        """Steps taken."""
    @property
    def dt(self) -> float:
        """The time step, s."""
    @property
    def duration(self) -> float:
        """The time ``run`` goes to, s."""
    @property
    def output_interval(self) -> float:
        """Time between output times, s."""
    @property
    def backend(self) -> Literal["cpu", "gpu"]:
        """The backend that runs."""
    @property
    def device(self) -> str:
        """The CPU or GPU adapter that runs."""
    @property
    def precision(self) -> Literal["f32", "f64"]:
        """The arithmetic."""
    @property
    def cable_names(self) -> List[str]:
        """_Cable names, in scenario order."""
    @property
    def body_names(self) -> List[str]:
        """Names of the vessel bodies that cable ends are attached to."""
    def advance(self, steps: int) -> None:
        """Advances ``steps`` time steps. Raises DivergedError on a blow-up."""
    def advance_to(self, t: float) -> None:
        """Advances to time ``t`` (s), to the step nearest it; a time already passed
        does nothing."""
    @overload
    def run(
        self, out_dir: None = None, format: Optional[Literal["csv", "parquet"]] = None
    ) -> "RunOutput":
        """Runs on to the end of the duration, keeping every output time in memory."""
    @overload
    def run(
        self,
        out_dir: Union[str, os.PathLike[str]],
        format: Optional[Literal["csv", "parquet"]] = None,
    ) -> Dict[str, Any]:
        """Runs on to the end of the duration, writing the output files into
        ``out_dir`` (as the command line does; ``format`` "csv" or "parquet", default
        the scenario's ``[output] format``); returns the summary."""
    def snapshot(self) -> "Snapshot":
        """Every cable's (and body's) state now (a copy)."""
    def positions(self, cable: _Cable) -> _FloatArray:
        """Node positions of a cable now: ``(nodes, 3)``, m."""
    def velocities(self, cable: _Cable) -> _FloatArray:
        """Node velocities of a cable now: ``(nodes, 3)``, m/s."""
    def tensions(self, cable: _Cable) -> _FloatArray:
        """Axial force per element of a cable now: ``(nodes - 1,)``, N."""
    def end_forces(self, cable: _Cable) -> _FloatArray:
        """The forces a cable exerts on its end supports now: ``(2, 3)``, row 0 the
        start, row 1 the end, N."""
    def end_force(self, cable: _Cable, end: _End = "end") -> _FloatArray:
        """The force a cable exerts now on the support at one end: ``(3,)``, N."""
    def body(self, body: _Body) -> "BodyState":
        """A vessel body's pose and cable load now."""
    def set_end_motion(
        self,
        cable: _Cable,
        end: _End,
        position: _Vec3,
        velocity: Optional[_Vec3] = None,
    ) -> None:
        """Drives one end of a cable from outside (a coupling loop): from now until the
        next call its target moves from ``position`` (m) at ``velocity`` (m/s; None:
        at rest) in a straight line and the end node follows it. The end must be held in the
        scenario (fixed or on a route); lumped-mass model on the CPU backend (the GPU
        path raises GpuError)."""
    def summary(self) -> Dict[str, Any]:
        """The summary of the run so far (the content of ``summary.json``)."""

@final
class Snapshot:
    """The state of every cable (and vessel body) at one time: a copy."""

    @property
    def time(self) -> float:
        """Simulated time, s."""
    @property
    def steps(self) -> int:
        """Steps taken."""
    @property
    def cable_names(self) -> List[str]:
        """_Cable names, in scenario order."""
    @property
    def body_names(self) -> List[str]:
        """Names of the vessel bodies."""
    def positions(self, cable: _Cable) -> _FloatArray:
        """Node positions: ``(nodes, 3)``, m."""
    def velocities(self, cable: _Cable) -> _FloatArray:
        """Node velocities: ``(nodes, 3)``, m/s."""
    def tensions(self, cable: _Cable) -> _FloatArray:
        """Axial force per element: ``(nodes - 1,)``, N."""
    def end_forces(self, cable: _Cable) -> _FloatArray:
        """Forces on the end supports: ``(2, 3)``, row 0 the start, row 1 the end, N."""
    def end_force(self, cable: _Cable, end: _End = "end") -> _FloatArray:
        """Force on the support at one end: ``(3,)``, N."""
    def winch(self, cable: _Cable) -> Optional[Dict[str, Any]]:
        """A winch cable's state (``deployed_length``, ``variable_l0`` in m,
        ``elements``, ``nodes_inserted``, ``nodes_deleted``,
        ``physical_coordinates`` in m), or None without a winch."""
    def body(self, body: _Body) -> "BodyState":
        """A vessel body's pose and cable load."""

@final
class BodyState:
    """A vessel body's pose and the load its cables exert on it, at one time."""

    @property
    def name(self) -> str: ...
    @property
    def position(self) -> _FloatArray:
        """Reference point: ``(3,)``, m."""
    @property
    def angles(self) -> _FloatArray:
        """Roll, pitch, yaw (the yaw includes the mean heading): ``(3,)``, degrees."""
    @property
    def force(self) -> _FloatArray:
        """Total force of the cables on the body: ``(3,)``, N."""
    @property
    def moment(self) -> _FloatArray:
        """Their moment about the reference point: ``(3,)``, N m."""

@final
class RunOutput:
    """Every output time of a run (t = 0 first) and its summary; series come with the
    output time first."""

    @property
    def times(self) -> _FloatArray:
        """Output times: ``(frames,)``, s."""
    @property
    def summary(self) -> Dict[str, Any]:
        """The run's summary (the content of ``summary.json``)."""
    @property
    def cable_names(self) -> List[str]:
        """_Cable names, in scenario order."""
    def __len__(self) -> int: ...
    def frame(self, i: int) -> Snapshot:
        """The state at output time ``i`` (negative from the last)."""
    def positions(self, cable: _Cable) -> _FloatArray:
        """``(frames, nodes, 3)``, m. ValueError for a winch cable whose node count
        changes: read each time with ``frame(i)``."""
    def velocities(self, cable: _Cable) -> _FloatArray:
        """``(frames, nodes, 3)``, m/s."""
    def tensions(self, cable: _Cable) -> _FloatArray:
        """``(frames, nodes - 1)``, N."""
    def end_forces(self, cable: _Cable) -> _FloatArray:
        """``(frames, 2, 3)``, ``[:, 0]`` the start, ``[:, 1]`` the end, N."""
    def body(self, body: _Body) -> Dict[str, _FloatArray]:
        """A body's series, each ``(frames, 3)``: ``position`` (m), ``angles``
        (degrees), ``force`` (N), ``moment`` (N m)."""
