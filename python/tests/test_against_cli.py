"""The package gives what the command line gives: the same run, the same numbers."""

import csv

import numpy as np

import cablesim
from conftest import run_cli

DURATION = 2.0  # s: a short run, long enough for a few output times


def read_end_forces(path):
    """end_forces.csv as {(time, cable, end): (fx, fy, fz)}."""
    with open(path, newline="") as f:
        return {
            (float(r["time"]), r["cable"], r["end"]): np.array(
                [float(r["fx"]), float(r["fy"]), float(r["fz"])]
            )
            for r in csv.DictReader(f)
        }


def test_fairlead_force_matches_cli_run(tmp_path, cli, catenary_path):
    out = tmp_path / "cli"
    run_cli(cli, "run", catenary_path, "--backend", "cpu", "--duration", DURATION,
            "--out", out, "--quiet")
    rust = read_end_forces(out / "end_forces.csv")

    sim = cablesim.Simulation.from_file(catenary_path, backend="cpu", duration=DURATION)
    run = sim.run()
    assert run.summary["status"] == "completed"
    assert run.times[-1] == DURATION
    forces = run.end_forces("line1")
    # Every output time, both ends, the same numbers: the CSV holds shortest
    # round-trip decimals, so the comparison can be exact.
    assert len(rust) == 2 * len(run.times)
    for k, t in enumerate(run.times):
        np.testing.assert_array_equal(forces[k, 0], rust[(t, "line1", "start")])
        np.testing.assert_array_equal(forces[k, 1], rust[(t, "line1", "end")])
    # A fairlead holding a 250 m wire in 100 m of water carries a real load.
    assert np.linalg.norm(forces[-1, 1]) > 1e3


def test_run_to_directory_writes_the_cli_files(tmp_path, cli, catenary_path):
    out = tmp_path / "cli"
    run_cli(cli, "run", catenary_path, "--backend", "cpu", "--duration", DURATION,
            "--out", out, "--quiet")
    sim = cablesim.Simulation.from_file(catenary_path, backend="cpu", duration=DURATION)
    summary = sim.run(tmp_path / "py")
    assert summary["status"] == "completed"
    assert summary["steps"] == sim.steps
    for name in ["end_forces.csv", "tensions.csv"]:
        assert (tmp_path / "py" / name).read_text() == (out / name).read_text(), name


def test_stepping_reaches_the_same_state_as_running(catenary_path):
    a = cablesim.Simulation.from_file(catenary_path, backend="cpu", duration=DURATION)
    b = cablesim.Simulation.from_file(catenary_path, backend="cpu", duration=DURATION)
    a.run()
    b.advance_to(DURATION / 2)
    b.advance(b.steps)  # as many steps again: to DURATION
    assert b.steps == a.steps
    assert b.time == a.time == DURATION
    np.testing.assert_array_equal(a.positions("line1"), b.positions("line1"))
    np.testing.assert_array_equal(a.end_forces(0), b.end_forces("line1"))
