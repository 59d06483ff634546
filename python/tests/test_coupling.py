"""Driving a fairlead from Python (a coupling loop) and reading the force back."""

import os
import signal
import threading

import numpy as np
import pytest

import cablesim

FAIRLEAD = np.array([0.0, 0.0, -10.0])  # m, the catenary example's held end
COUPLING_DT = 0.1  # s, the outer solver's step


def drive(sim, offset, move, hold):
    """Moves the fairlead by `offset` (m) at a steady speed over `move` seconds, then
    holds it there for `hold` seconds, setting the motion at each coupling step as an
    outer solver would; returns the coupling times (s) and the fairlead force (N) read
    back after each step."""
    offset = np.asarray(offset, dtype=float)
    velocity = offset / move
    t0 = sim.time
    times, forces = [], []
    for k in range(int(round((move + hold) / COUPLING_DT))):
        t = k * COUPLING_DT
        if t < move:
            sim.set_end_motion("line1", "end", FAIRLEAD + velocity * t, velocity)
        else:
            sim.set_end_motion("line1", "end", FAIRLEAD + offset)
        sim.advance_to(t0 + t + COUPLING_DT)
        times.append(sim.time - t0)
        forces.append(sim.end_force("line1", "end"))
    return np.array(times), np.array(forces)


def static_fairlead_force(repo, offset):
    """The fairlead force of the catenary relaxed with its fairlead at the offset: the
    static equilibrium the driven line oscillates about."""
    text = (repo / "examples" / "catenary.toml").read_text()
    x, y, z = (float(c) for c in FAIRLEAD + np.asarray(offset))
    held = f"end = {{ fixed = [{x!r}, {y!r}, {z!r}] }}"
    text = text.replace("end = { fixed = [0.0, 0.0, -10.0] }", held)
    assert held in text
    return cablesim.Simulation.from_toml(text, backend="cpu").end_force("line1")


@pytest.mark.parametrize("dx", [3.0, -3.0])
def test_driven_fairlead_load_follows_its_position(repo, catenary_path, dx):
    """Move the fairlead 3 m away from the anchor (tauter) or toward it (slacker): the
    load read back swings about, and on average settles at, the static load of the
    line with its fairlead there, about 25% from where it started."""
    offset = [dx, 0.0, 0.0]
    sim = cablesim.Simulation.from_file(catenary_path, backend="cpu")
    f0 = sim.end_force("line1")
    times, forces = drive(sim, offset, move=10.0, hold=30.0)
    # The fairlead went where it was sent.
    np.testing.assert_allclose(sim.positions("line1")[-1], FAIRLEAD + offset, atol=1e-6)
    expected = static_fairlead_force(repo, offset)
    # The target really is a different load (tauter: the cable pulls harder toward
    # the anchor, -x).
    assert (abs(expected[0]) > 1.2 * abs(f0[0])) if dx > 0 else (abs(expected[0]) < 0.85 * abs(f0[0]))
    settled = forces[times > 20.0].mean(axis=0)
    np.testing.assert_allclose(settled, expected, rtol=0.01, atol=1.0)
    # The force read back at each coupling step is the snapshot's.
    np.testing.assert_array_equal(forces[-1], sim.snapshot().end_forces("line1")[1])


def test_holding_still_keeps_the_load(catenary_path):
    """The relaxed catenary held where it is: the coupling loop itself adds nothing."""
    sim = cablesim.Simulation.from_file(catenary_path, backend="cpu")
    f0 = sim.end_force("line1")
    _, forces = drive(sim, [0.0, 0.0, 0.0], move=1.0, hold=1.0)
    np.testing.assert_allclose(forces, np.broadcast_to(f0, forces.shape), rtol=1e-3, atol=1.0)


def test_an_end_that_is_not_held_cannot_be_driven(repo):
    text = (repo / "examples" / "catenary.toml").read_text()
    text = text.replace("end = { fixed = [0.0, 0.0, -10.0] }",
                        "end = { free = [0.0, 0.0, -10.0] }")
    sim = cablesim.Simulation.from_toml(text, backend="cpu", duration=1.0)
    with pytest.raises(cablesim.CablesimError, match="held"):
        sim.set_end_motion("line1", "end", FAIRLEAD)


def test_ctrl_c_interrupts_stepping(catenary_path):
    """Stepping releases the GIL (the timer thread runs meanwhile) and looks at the
    signals between chunks: SIGINT stops a long advance with KeyboardInterrupt."""
    sim = cablesim.Simulation.from_file(catenary_path, backend="cpu", duration=1e5)
    timer = threading.Timer(0.3, os.kill, (os.getpid(), signal.SIGINT))
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            sim.advance_to(1e5)
    finally:
        timer.cancel()
    assert 0 < sim.time < 1e5
    # The simulation is still usable after the interrupt.
    steps = sim.steps
    sim.advance(3)
    assert sim.steps == steps + 3
