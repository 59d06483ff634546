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
