"""Shared fixtures of the Python package's tests: the repository's paths and the
command-line binary the package is compared with."""

import os
import pathlib
import shutil
import subprocess

import pytest

REPO = pathlib.Path(__file__).resolve().parents[2]
CATENARY = REPO / "examples" / "catenary.toml"


@pytest.fixture(scope="session")
def repo() -> pathlib.Path:
    return REPO


@pytest.fixture(scope="session")
def catenary_path() -> pathlib.Path:
    return CATENARY


@pytest.fixture(scope="session")
def cli() -> list:
    """The `cablesim` command: $CABLESIM_BIN, else the release build in target/
    (which `cargo test --release` leaves there), else `cargo run --release`."""
    env = os.environ.get("CABLESIM_BIN")
    if env:
        return [env]
    built = REPO / "target" / "release" / "cablesim"
    if built.exists():
        return [str(built)]
    cargo = shutil.which("cargo")
    if cargo is None:
        pytest.fail("no cablesim binary: set CABLESIM_BIN or build with cargo")
    return [cargo, "run", "--quiet", "--release", "--manifest-path",
            str(REPO / "Cargo.toml"), "--bin", "cablesim", "--"]


def run_cli(cli, *args):
    """Runs the command line; a failure shows its output."""
    r = subprocess.run([*cli, *map(str, args)], capture_output=True, text=True)
    assert r.returncode == 0, f"cablesim {' '.join(map(str, args))} failed:\n{r.stderr}"
    return r
