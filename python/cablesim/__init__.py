"""cablesim: lumped-mass dynamics of underwater cables (mooring lines, towed cables,
net cages), many at once, from Python.

    import cablesim
    sim = cablesim.Simulation.from_file("examples/catenary.toml", backend="cpu")
    sim.advance_to(10.0)                       # s
    print(sim.end_force("line1", "end"))       # N, the fairlead load
    out = sim.run()                            # on to the end, kept in memory
    print(out.end_forces("line1").shape)       # (frames, 2, 3)

Units are SI throughout (m, s, N, kg). Cables and bodies are chosen by index
(scenario order) or by name; cable ends are "start" and "end".
"""

from ._cablesim import (
    BodyState,
    CablesimError,
    DivergedError,
    GpuError,
    OutputError,
    RunOutput,
    ScenarioError,
    Simulation,
    Snapshot,
    __version__,
    run_study,
)

__all__ = [
    "run_study",
    "BodyState",
    "CablesimError",
    "DivergedError",
    "GpuError",
    "OutputError",
    "RunOutput",
    "ScenarioError",
    "Simulation",
    "Snapshot",
    "__version__",
]
