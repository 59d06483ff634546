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
