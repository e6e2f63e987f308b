"""p = 3 (hertz-3p): points as sequences and (n, 3) arrays, against the CLI to the last digit."""

import json

import numpy as np
import pytest

import contactrb
from conftest import cli_json, run_cli


def text(mu):
    return ",".join(repr(float(v)) for v in mu)


def test_hf_solve_equals_cli(tmp_path):
    mu = [0.31, 1.05, 20.0]
    run_cli("solve", "--case", "hertz-3p", "--mu", text(mu), "--out", tmp_path)
    j = json.loads((tmp_path / "solution.json").read_text())
    r = contactrb.Case("hertz-3p").solve(mu)
    assert (r.energy, r.force, r.iterations) == (j["energy"], j["contact_force"], j["iterations"])
    assert np.array_equal(r.mu, mu)


def test_model_of_python_snapshots_answers_as_the_cli(tmp_path):
    case = contactrb.Case("hertz-3p")
    training = case.set("training")[::125]  # 8 of the 1000 points
    model = contactrb.offline(contactrb.snapshots(case, training, jobs=2))
    path = tmp_path / "model.h5"
    model.save(str(path))
    assert model.parameter_names == case.parameter_names
    points = np.array([[0.2, 0.95, 10.0], [0.31, 1.05, 20.0], [0.44, 1.1, 28.0]])
    batch = tmp_path / "batch.txt"
    batch.write_text("".join(text(p) + "\n" for p in points))
    lines = [json.loads(s) for s in run_cli("online", "--model", path, "--batch", batch, check=False).stdout.splitlines()]
    many = model.solve_many(points)
    assert len(lines) == len(points)
    for i, (p, j) in enumerate(zip(points, lines)):
        r = model.solve(p)
        assert r.energy == j["energy"] == many["energy"][i]
        assert r.force == j["contact_force"] == many["force"][i]
        assert r.coefficients.tolist() == j["u_hat"] == many["coefficients"][i].tolist()
        assert r.status == j["status"] == contactrb.STATUS[many["status"][i]]
    j = cli_json("online", "--model", path, "--mu", text(points[1]))  # one --mu: a fresh solver
    assert model.solve(points[1]).energy == j["energy"]
    # A point of the wrong size: the library's message (the CLI says it about --mu before the
    # library sees the point).
    with pytest.raises(contactrb.Error, match=r"needs 3 values \(delta, R2, E2\), got 2"):
        model.solve([0.3, 1.0])
    with pytest.raises(contactrb.Error, match="columns, the model has 3 parameters"):
        model.solve_many(np.zeros((4, 2)))
