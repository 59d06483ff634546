"""Vessel bodies from Python: their pose and the load of their cables, now and as
series."""

import re

import numpy as np

import cablesim

SURGE = 2.0  # m, amplitude of the barge's surge
PERIOD = 8.0  # s
DURATION = 3.0  # s


def barge(repo, tmp_path):
    """The book's barge example (docs/src/bodies.md), surging in a motion file."""
    doc = (repo / "docs" / "src" / "bodies.md").read_text()
    toml = re.search(r"## Example\s+```toml\n(.*?)```", doc, re.S).group(1)
    rows = ["t,x,y,z,roll,pitch,yaw"]
    for t in np.arange(0.0, DURATION + 1.0, 0.25):
        rows.append(f"{t},{SURGE * np.sin(2 * np.pi * t / PERIOD)},0,0,0,0,0")
    (tmp_path / "barge_motion.csv").write_text("\n".join(rows) + "\n")
    path = tmp_path / "barge.toml"
    path.write_text(toml)
    return path


def test_body_state_and_series(repo, tmp_path):
    sim = cablesim.Simulation.from_file(barge(repo, tmp_path), backend="cpu",
                                        duration=DURATION)
    assert sim.body_names == ["barge"]
    out = sim.run()
    frames = len(out)
    series = out.body("barge")
    for key in ["position", "angles", "force", "moment"]:
        assert series[key].shape == (frames, 3), key
    # The heading is 15 degrees: the surge runs along that axis.
    heading = np.radians(15.0)
    for k, t in enumerate(out.times):
        surge = SURGE * np.sin(2 * np.pi * t / PERIOD)
        np.testing.assert_allclose(series["position"][k],
                                   [surge * np.cos(heading), surge * np.sin(heading), 0.0],
                                   atol=1e-6)
    # The body's load is what its two cables exert at their ends on it.
    ends = out.end_forces("bow")[:, 1] + out.end_forces("stern")[:, 1]
    np.testing.assert_allclose(series["force"], ends, rtol=1e-9, atol=1e-6)
    # Now, as a BodyState.
    b = sim.body("barge")
    assert b.name == "barge"
    np.testing.assert_array_equal(b.force, series["force"][-1])
    np.testing.assert_array_equal(b.angles, series["angles"][-1])
    assert np.linalg.norm(b.force) > 1e3
