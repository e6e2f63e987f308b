"""A row-cone model (`contactrb offline --dual rows`) from Python: load, solve with every iteration
(the reduced Newton included), solve_many and evaluate, against the CLI to the last digit and
against the HF snapshots it was built from."""

import json

import numpy as np
import pytest

import contactrb
from conftest import cli_error, cli_json, run_cli

POINTS = [0.16, 0.2625, 0.3, 0.41, 0.45]


@pytest.fixture(scope="module")
def rows_model_path(workdir, cli_snapshots):
    path = workdir / "rows_model" / "model.h5"
    path.parent.mkdir()
    run_cli("offline", "--snapshots", cli_snapshots, "--dual", "rows", "--out", path)
    return path


@pytest.fixture(scope="module")
def rows_model(rows_model_path):
    return contactrb.Model.load(str(rows_model_path))


def online_json(model_path, mu, *extra):
    return cli_json("online", "--model", model_path, "--mu", repr(mu), *extra)


def assert_equals_cli(r, j):
    assert (r.converged, r.status, r.iterations) == (j["converged"], j["status"], j["iterations"])
    assert (r.energy, r.force) == (j["energy"], j["contact_force"])
    assert r.coefficients.tolist() == j["u_hat"]
    assert r.multipliers.tolist() == j["lambda_hat"]
    assert r.estimate_parts == j["estimate"]
    assert r.sizes == j["sizes"]


@pytest.mark.parametrize("iteration", ["automatic", "newton"])
@pytest.mark.parametrize("mu", [0.16, 0.3, 0.41])
def test_solve_equals_cli_online(rows_model, rows_model_path, mu, iteration):
    r = rows_model.solve(mu, iteration=iteration)
    assert r.converged
    assert_equals_cli(r, online_json(rows_model_path, mu, "--iteration", iteration))


def test_one_dual_generator_per_kept_row(rows_model, rows_model_path):
    report = json.loads((rows_model_path.parent / "offline.json").read_text())
    assert rows_model.sizes["R"] == report["compression"]["kept"] == report["dual"]["R"]
    r = rows_model.solve(0.41, iteration="newton")
    assert (r.multipliers >= 0.0).all()
    # The row cone's reduced pressure is the HF pressure on the kept rows: its reconstruction holds
    # lambda_hat itself, on R of the HF rows, and nothing on the others.
    lam = rows_model.fields(r)["multipliers"]
    assert np.count_nonzero(lam) == np.count_nonzero(r.multipliers)
    assert sorted(lam[lam > 0].tolist()) == sorted(r.multipliers[r.multipliers > 0].tolist())


def test_newton_reproduces_the_training_snapshots(rows_model, cli_snapshots):
    snaps = contactrb.Snapshots.load(str(cli_snapshots))
    for i, mu in enumerate(snaps.mu[:, 0]):
        r = rows_model.solve(mu, iteration="newton")
        assert r.converged
        # The reduced Newton's pair satisfies the contact conditions at its own rows exactly.
        parts = r.estimate_parts
        assert abs(parts["violation"]) < 1e-12 and abs(parts["complementarity"]) < 1e-12, parts
        f = rows_model.fields(r)
        lam_hf = snaps.multipliers[i]
        err = np.linalg.norm(f["multipliers"] - lam_hf) / np.linalg.norm(lam_hf)
        assert err < 1e-3, (mu, err)
        u_hf = snaps.u[i]
        u_rb = f["displacement"].reshape(-1)
        assert np.linalg.norm(u_rb - u_hf) < 1e-4 * np.linalg.norm(u_hf), mu


def test_solve_many_newton_equals_cli_batch(rows_model, rows_model_path, tmp_path):
    batch = tmp_path / "batch.txt"
    batch.write_text("".join(f"{mu!r}\n" for mu in POINTS))
    out = run_cli("online", "--model", rows_model_path, "--batch", batch, "--iteration", "newton").stdout
    lines = [json.loads(line) for line in out.splitlines()]
    many = rows_model.solve_many(np.array(POINTS), iteration="newton")
    threads = rows_model.solve_many(np.array(POINTS), iteration="newton", jobs=2)
    for i, j in enumerate(lines):
        assert many["energy"][i] == j["energy"] == threads["energy"][i]
        assert many["iterations"][i] == j["iterations"]
        assert many["u_hat"][i].tolist() == j["u_hat"] == threads["u_hat"][i].tolist()
        assert many["lambda_hat"][i].tolist() == j["lambda_hat"]
        assert many["estimate"][i] == j["estimate"]["energy"]
    # The peak pressure of each answer is the largest reduced multiplier (row-cone generators are
    # unit rows).
    assert np.array_equal(many["peak_pressure"], many["lambda_hat"].max(axis=1))


def test_evaluate_newton_equals_cli(rows_model, rows_model_path, tmp_path):
    points = [0.2, 0.33]
    values = tmp_path / "values.txt"
    values.write_text("".join(f"{mu!r}\n" for mu in points))
    run_cli("evaluate", "--model", rows_model_path, "--set", values, "--repeats", 1, "--iteration", "newton", "-q",
            "--out", tmp_path / "ev")
    j = json.loads((tmp_path / "ev" / "evaluation.json").read_text())
    assert j["iteration"] == "newton"
    e = contactrb.evaluate(rows_model, np.array(points), repeats=1, iteration="newton")
    assert e["iteration"] == "newton"
    rows = np.genfromtxt(tmp_path / "ev" / "evaluation.csv", delimiter=",", names=True)
    for key in ["energy_rb", "e_displ", "e_press", "estimate", "rb_iterations"]:
        assert np.array_equal(e[key], rows[key]), key
    # The row cone holds every non-negative pressure on the kept rows.
    assert (e["e_press_cone"] == 0.0).all()
    assert e["summary"]["max_e_press"] < 1e-2


def test_newton_on_a_global_cone_is_refused_as_by_the_cli(cli_snapshots, tmp_path):
    cli_model = tmp_path / "cpg.h5"
    run_cli("offline", "--snapshots", cli_snapshots, "--dual", "cpg", "--out", cli_model)
    model = contactrb.Model.load(str(cli_model))
    message = cli_error("online", "--model", cli_model, "--mu", "0.3", "--iteration", "newton")
    assert message.startswith("--iteration newton needs a model built with `contactrb offline --dual rows`")
    with pytest.raises(contactrb.Error, match="iteration 'newton' needs a model built with dual 'rows'"):
        model.solve(0.3, iteration="newton")
    with pytest.raises(contactrb.Error, match="iteration 'newton'"):
        model.solve_many(np.array([0.3]), iteration="newton")
    with pytest.raises(contactrb.Error, match="iteration 'newton'"):
        contactrb.evaluate(model, np.array([0.3]), iteration="newton")
    with pytest.raises(contactrb.Error, match="online iteration"):
        model.solve(0.3, iteration="fast")


def test_python_offline_rows_equals_cli_model(rows_model, cli_snapshots):
    snaps = contactrb.Snapshots.load(str(cli_snapshots))
    m = contactrb.offline(snaps, dual="rows")
    assert m.sizes == rows_model.sizes
    for mu in POINTS:
        a, b = m.solve(mu, iteration="newton"), rows_model.solve(mu, iteration="newton")
        assert a.energy == b.energy and np.array_equal(a.multipliers, b.multipliers)
