"""A study run from Python gives the command line's tables, byte for byte."""

import json

import cablesim
from conftest import run_cli


def test_run_study_matches_the_command_line(repo, cli, tmp_path):
    study = repo / "examples" / "study_spread_mooring.toml"
    got = cablesim.run_study(study, tmp_path / "py")
    run_cli(cli, "study", "run", study, "--out", tmp_path / "cli", "--quiet")
    for name in ("study.csv", "members.csv", "study.json"):
        assert (tmp_path / "py" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes(), name
    # The returned dict is study.json, and it holds a fit per sea state and channel.
    assert got == json.loads((tmp_path / "cli" / "study.json").read_text())
    text = (tmp_path / "py" / "study.csv").read_text()
    assert "mpm" in text.splitlines()[0].lower()


def test_run_study_errors_name_the_file(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text("[study]\nseeds = 0\n")
    try:
        cablesim.run_study(bad, tmp_path / "out")
    except cablesim.CablesimError as e:
        assert "bad.toml" in str(e)
    else:
        raise AssertionError("a bad study file must raise")


def test_run_study_packed_gives_the_members_own_results(repo, cli, tmp_path):
    # backend="auto" packs the members into one run (on this machine's software
    # adapter the packed model runs on the CPU): every member steps as it does alone,
    # so the tables equal the command line's member-by-member CPU run byte for byte.
    study = repo / "examples" / "study_spread_mooring.toml"
    cablesim.run_study(study, tmp_path / "packed", backend="auto", batch=4)
    run_cli(cli, "study", "run", study, "--out", tmp_path / "cli", "--quiet")
    for name in ("study.csv", "members.csv", "study.json"):
        assert (tmp_path / "packed" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes(), name


def test_run_study_rejects_a_bad_backend_by_name(repo, tmp_path):
    study = repo / "examples" / "study_spread_mooring.toml"
    for kwargs, word in (({"backend": "tpu"}, "backend"), ({"batch": 0}, "batch")):
        try:
            cablesim.run_study(study, tmp_path / "out", **kwargs)
        except ValueError as e:
            assert word in str(e), e
        else:
            raise AssertionError(f"{kwargs} must raise ValueError")


def _buoy_study(path, study):
    """The free buoy on three lines of tests/cli/study_conditions.rs, with `study`."""
    text = """
[simulation]
duration = 10.0
output_interval = 1.0

[environment]
depth = 50.0

[environment.waves]
ramp = 5.0

[[line_types]]
name = "rope"
diameter = 0.05
mass_per_length = 2.5
ea = 1.0e7
damping = 2.0e-3
cn = 1.2
ct = 0.2
cm = 1.0

[[bodies]]
name = "buoy"
motion = "free"
reference = [0.0, 0.0, -20.0]
mass = 2000.0
cg = [0.0, 0.0, -0.5]
inertia = [2000.0, 2000.0, 3000.0]
volume = 3.0
ca = [1.0, 1.0, 1.0]
drag_area = [2.0, 2.0, 2.0]
damping = [[1500.0, 0, 0, 0, 0, 0], [0, 1500.0, 0, 0, 0, 0], [0, 0, 3000.0, 0, 0, 0], [0, 0, 0, 2.0e4, 0, 0], [0, 0, 0, 0, 2.0e4, 0], [0, 0, 0, 0, 0, 500.0]]
"""
    import math
    for k in range(3):
        a = math.radians(120.0 * k)
        text += f"""
[[cables]]
name = "leg{k}"
line_type = "rope"
length = 68.0
segments = 20
initial = "catenary"
start = {{ fixed = [{60.0 * math.cos(a)}, {60.0 * math.sin(a)}, -50.0] }}
end = {{ body = "buoy", at = [{1.5 * math.cos(a)}, {1.5 * math.sin(a)}, -1.0] }}
"""
    path.write_text(text + study)
    return path


ALL_LIMIT_STATES = """
[study]
seed = 3
seeds = 2
duration = 40.0
transient = 10.0
sea_states = [
  { name = "fatigue", hs = 0.5, tp = 6.0, probability = 1.0 },
  { name = "extreme", hs = 1.0, tp = 7.0 },
]

[study.conditions]
broken = ["leg0", "leg2"]

[study.design]
consequence_class = 2
capacities = { rope = 1.0e5 }

[study.fatigue]
design_fatigue_factor = 3.0

[fatigue]
[fatigue.line_types.rope]
curve = "spiral_rope"
area_m2 = 0.00098
"""


def test_run_study_returns_conditions_governing_and_fatigue(cli, tmp_path):
    # One study of all three limit states: the returned dict (study.json) holds each
    # condition's sea states with its limit state and factors, the governing condition
    # and line per limit state, the buoy's offset, and the fatigue of the intact
    # mooring; the files equal the command line's, fatigue.csv among them.
    study = _buoy_study(tmp_path / "all.toml", ALL_LIMIT_STATES)
    got = cablesim.run_study(study, tmp_path / "py")
    run_cli(cli, "study", "run", study, "--out", tmp_path / "cli", "--quiet")
    for name in ("study.csv", "members.csv", "study.json", "fatigue.csv"):
        assert (tmp_path / "py" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes(), name
    assert got["members"] == 2 * 2 + 2 * 2  # intact: 2 sea states; each broken line: 1
    states = [(s["condition_name"], s["index"], s["limit_state"]) for s in got["sea_states"]]
    assert states == [("intact", 0, "uls"), ("intact", 1, "uls"), ("leg0", 1, "als"), ("leg2", 1, "als")]
    for s in got["sea_states"]:
        factors = {(c["design"]["mean_factor"], c["design"]["dynamic_factor"])
                   for c in s["channels"] if c["design"]}
        assert factors == ({(1.4, 2.1)} if s["limit_state"] == "uls" else {(1.0, 1.25)}), s["condition_name"]
        # The broken line is not checked in its own condition.
        broken = [c for c in s["channels"] if c["channel"].startswith(s["condition_name"] + ".")]
        if s["limit_state"] == "als":
            assert broken and all(c["design"] is None for c in broken)
        names = [c["channel"] for c in s["channels"]]
        assert "buoy.offset" in names
    gov = got["governing"]
    assert [g["limit_state"] for g in gov] == ["uls", "als"]
    worst = max((c for c in got["conditions"] if c["limit_state"] == "als"), key=lambda c: c["utilisation"])
    assert gov[1]["condition_name"] == worst["condition_name"]
    assert gov[1]["line"] != gov[1]["condition_name"]
    # Fatigue: per location, the sea states of the intact mooring and the life.
    assert len(got["fatigue"]) == 6
    for loc in got["fatigue"]:
        assert [s["seeds"] for s in loc["sea_states"]] == [2, 2]
        assert loc["life"] == 1.0 / (3.0 * loc["annual_damage"])


def test_run_study_fatigue_table_recomputes_from_the_members(repo, cli, tmp_path):
    # The fatigue study of the examples: study.json's fatigue is fatigue.csv's, and
    # each location's annual damage is the sum of its sea states' shares.
    study = repo / "examples" / "study_spread_mooring.toml"
    text = study.read_text()
    start = text.index("sea_states = [")
    end = text.index("]\n", start) + 2
    rows = """sea_states = [
  { name = "calm", hs = 1.0, tp = 7.0, probability = 0.7 },
  { name = "rough", hs = 3.0, tp = 9.0, probability = 0.3 },
]
"""
    text = text[:start] + rows + text[end:]
    text = text.replace("seeds = 3\n", "seeds = 2\n")
    text += """
[study.fatigue]
design_fatigue_factor = 10.0

[fatigue]
[fatigue.line_types.wire]
curve = "spiral_rope"
area_m2 = 0.00098
"""
    p = tmp_path / "fatigue_study.toml"
    p.write_text(text)
    got = cablesim.run_study(p, tmp_path / "py")
    import csv
    with open(tmp_path / "py" / "fatigue.csv", newline="") as f:
        table = list(csv.DictReader(f))
    assert len(table) == 3 * 2 * 2  # 3 lines x 2 ends x 2 sea states
    for loc in got["fatigue"]:
        shares = [s["annual_damage"] for s in loc["sea_states"]]
        assert all(x > 0 for x in shares)
        assert abs(sum(shares) - loc["annual_damage"]) <= 1e-12 * loc["annual_damage"]
        assert loc["design_fatigue_factor"] == 10.0
        mine = [r for r in table if r["cable"] == loc["cable"] and r["location"] == str(loc["location"])]
        assert len(mine) == 2, loc
        assert float(mine[0]["life"]) == loc["life"]
