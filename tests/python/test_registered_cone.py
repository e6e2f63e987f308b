"""A registered-cone model (`contactrb offline --dual registered`) from Python: built by the CLI
and by contactrb.offline from the same level-2 snapshots (the same arrays), solved against the CLI
to the last digit, and its reconstructed pressure: non-negative, spread over more HF rows than it
has generators, against the HF pressure at a training value (unweighted relative L2)."""

import json

import numpy as np
import pytest

import contactrb
from conftest import cli_json, run_cli

VALUES = "0.15,0.2,0.25,0.3,0.35,0.4,0.45"


@pytest.fixture(scope="module")
def level2_snapshots(workdir):
    path = workdir / "registered" / "snapshots.h5"
    path.parent.mkdir()
    run_cli("snapshots", "--case", "hertz-a", "--level", "2", "--values", VALUES, "-j", "2", "-q", "--out", path)
    return path


@pytest.fixture(scope="module")
def model_path(level2_snapshots):
    path = level2_snapshots.parent / "model.h5"
    run_cli("offline", "--snapshots", level2_snapshots, "--dual", "registered", "--r", "5", "--out", path)
    return path


@pytest.fixture(scope="module")
def model(model_path):
    return contactrb.Model.load(str(model_path))


@pytest.mark.parametrize("mu", [0.17, 0.3, 0.43])
def test_solve_equals_cli_online(model, model_path, mu):
    r = model.solve(mu)
    j = cli_json("online", "--model", model_path, "--mu", repr(mu))
    assert r.converged and j["converged"]
    assert r.multipliers.tolist() == j["lambda_hat"]
    assert r.coefficients.tolist() == j["u_hat"]
    assert r.sizes == j["sizes"] and r.sizes["R"] == 5


def test_python_offline_builds_the_same_model(model, level2_snapshots):
    built = contactrb.offline(str(level2_snapshots), dual="registered", R=5)
    assert built.sizes == model.sizes
    assert built.solve(0.27).multipliers.tolist() == model.solve(0.27).multipliers.tolist()


def test_pressure_follows_the_hf_pressure(model, model_path, level2_snapshots):
    report = json.loads((model_path.parent / "offline.json").read_text())
    assert report["dual"]["method"] == "registered" and report["dual"]["R"] == 5
    snapshots = contactrb.Snapshots.load(str(level2_snapshots))
    r = model.solve(0.3)
    lam = model.fields(r)["multipliers"]
    assert (lam >= 0.0).all()
    assert np.count_nonzero(lam) > 2 * 5  # generators that are profiles, not rows
    hf = snapshots.multipliers[3]  # mu = 0.3
    assert snapshots.mu[3].tolist() == [0.3]
    assert np.linalg.norm(lam - hf) / np.linalg.norm(hf) < 5e-2
