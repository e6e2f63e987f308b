"""Shared fixtures of the Python module tests (docs/python.md, docs/testing.md).

Run by ctest (tests/python/CMakeLists.txt) with PYTHONPATH=<build>/python and CONTACTRB_CLI set to
the command-line binary; the CLI makes the reference files the module's results are compared with.
"""

import json
import os
import subprocess

import pytest

import contactrb

# hertz-a: five training values of its displacement parameter (as tests/cli/test_cli_offline_online.cpp).
VALUES = "0.15,0.225,0.3,0.375,0.45"


def cli_path():
    path = os.environ.get("CONTACTRB_CLI")
    if not path:
        pytest.skip("CONTACTRB_CLI is not set (run through ctest)")
    return path


def run_cli(*args, check=True):
    """Runs the CLI; returns the CompletedProcess (stdout, stderr as text)."""
    r = subprocess.run([cli_path(), *map(str, args)], capture_output=True, text=True)
    if check and r.returncode != 0:
        raise AssertionError(f"contactrb {' '.join(map(str, args))} failed ({r.returncode}):\n{r.stdout}\n{r.stderr}")
    return r


def cli_error(*args):
    """The message of a failing CLI run: its stderr line 'contactrb: error: <message>'."""
    r = run_cli(*args, check=False)
    assert r.returncode != 0, r.stdout
    prefix = "contactrb: error: "
    line = r.stderr.strip()
    assert line.startswith(prefix), line
    return line[len(prefix):]


def cli_json(*args):
    return json.loads(run_cli(*args).stdout)


@pytest.fixture(scope="session")
def cli():
    return cli_path()


@pytest.fixture(scope="session")
def workdir(tmp_path_factory):
    return tmp_path_factory.mktemp("contactrb_python")


@pytest.fixture(scope="session")
def cli_snapshots(workdir, cli):
    path = workdir / "snapshots.h5"
    run_cli("snapshots", "--case", "hertz-a", "--values", VALUES, "-j", "2", "-q", "--out", path)
    return path


@pytest.fixture(scope="session")
def cli_model(workdir, cli_snapshots):
    path = workdir / "cli_model" / "model.h5"
    path.parent.mkdir()
    run_cli("offline", "--snapshots", cli_snapshots, "--out", path)
    return path


@pytest.fixture(scope="session")
def model(cli_model):
    return contactrb.Model.load(str(cli_model))
