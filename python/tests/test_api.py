"""Shapes of what the package hands out, and errors that say where the problem is."""

import numpy as np
import pytest

import cablesim

SEGMENTS = 50  # the catenary example's line1


def test_snapshot_shapes(catenary_path):
    sim = cablesim.Simulation.from_file(catenary_path, backend="cpu", duration=3.0)
    assert sim.cable_names == ["line1"]
    assert sim.body_names == []
    assert sim.time == 0.0 and sim.steps == 0 and sim.dt > 0
    s = sim.snapshot()
    assert s.positions("line1").shape == (SEGMENTS + 1, 3)
    assert s.velocities(0).shape == (SEGMENTS + 1, 3)
    assert s.tensions(-1).shape == (SEGMENTS,)
    assert s.end_forces("line1").shape == (2, 3)
    assert s.end_force("line1", "start").shape == (3,)
    assert s.positions("line1").dtype == np.float64
    # The ends are where the scenario put them.
    np.testing.assert_allclose(s.positions("line1")[0], [-220.0, 0.0, -100.0], atol=1e-9)
    np.testing.assert_allclose(s.positions("line1")[-1], [0.0, 0.0, -10.0], atol=1e-9)
    assert s.winch("line1") is None


def test_run_output_shapes(catenary_path):
    sim = cablesim.Simulation.from_file(catenary_path, backend="cpu", duration=3.0)
    out = sim.run()
    frames = 4  # t = 0, 1, 2, 3 s at the example's 1 s output interval
    assert len(out) == frames
    np.testing.assert_allclose(out.times, [0.0, 1.0, 2.0, 3.0])
    assert out.positions("line1").shape == (frames, SEGMENTS + 1, 3)
    assert out.velocities("line1").shape == (frames, SEGMENTS + 1, 3)
    assert out.tensions("line1").shape == (frames, SEGMENTS)
    assert out.end_forces("line1").shape == (frames, 2, 3)
    # The series are the frames stacked.
    np.testing.assert_array_equal(out.tensions("line1")[2], out.frame(2).tensions("line1"))
    np.testing.assert_array_equal(out.end_forces("line1")[-1], out.frame(-1).end_forces(0))
    assert out.summary["cables"][0]["name"] == "line1"


def test_bad_field_names_file_and_field(repo):
    text = (repo / "examples" / "catenary.toml").read_text()
    text = text.replace("length = 250.0", "length = -250.0")
    with pytest.raises(cablesim.ScenarioError) as e:
        cablesim.Simulation.from_toml(text, name="mooring.toml")
    assert e.value.path == "mooring.toml"
    assert e.value.field.startswith("cables[0]") and "length" in e.value.field
    assert "mooring.toml" in str(e.value) and "length" in str(e.value)


def test_wrong_type_names_the_field():
    with pytest.raises(cablesim.ScenarioError) as e:
        cablesim.Simulation.from_toml('[simulation]\nduration = "long"\n', name="x.toml")
    assert "simulation.duration" in e.value.field


def test_missing_file_names_it(tmp_path):
    path = tmp_path / "nowhere.toml"
    with pytest.raises(cablesim.ScenarioError) as e:
        cablesim.Simulation.from_file(path)
    assert str(path) in str(e.value)


def test_unknown_option_lists_the_names(catenary_path):
    with pytest.raises(ValueError, match='backend: must be auto, cpu or gpu, got "tpu"'):
        cablesim.Simulation.from_file(catenary_path, backend="tpu")


def test_unknown_cable_and_end(catenary_path):
    sim = cablesim.Simulation.from_file(catenary_path, backend="cpu", duration=1.0)
    with pytest.raises(KeyError, match="line1"):
        sim.positions("line9")
    with pytest.raises(IndexError):
        sim.tensions(3)
    with pytest.raises(ValueError, match="start"):
        sim.end_force("line1", "top")


def test_overrides_apply(catenary_path):
    sim = cablesim.Simulation.from_file(catenary_path, backend="cpu", dt=1e-3, duration=0.5)
    assert sim.dt == pytest.approx(1e-3)
    assert sim.duration == 0.5
    assert sim.backend == "cpu" and sim.precision == "f64"
    out = sim.run()
    assert out.times[-1] == pytest.approx(0.5)
    assert sim.steps == round(0.5 / 1e-3)


def test_ancf_model_through_the_same_calls(catenary_path):
    """The ANCF reference model (stepped in one piece, not in chunks) answers the same
    calls, and its fairlead load agrees with the lumped-mass model's on the relaxed
    catenary."""
    ancf = cablesim.Simulation.from_file(catenary_path, formulation="ancf", duration=1.0)
    lumped = cablesim.Simulation.from_file(catenary_path, backend="cpu", duration=1.0)
    a, b = ancf.run(), lumped.run()
    np.testing.assert_allclose(a.times, b.times)
    assert ancf.time == pytest.approx(1.0)
    np.testing.assert_allclose(a.end_forces("line1")[-1, 1], b.end_forces("line1")[-1, 1],
                               rtol=2e-3)
    with pytest.raises(cablesim.CablesimError, match="lumped-mass"):
        ancf.set_end_motion("line1", "end", [0.0, 0.0, -10.0])
