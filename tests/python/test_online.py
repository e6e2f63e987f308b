"""Snapshots, offline and online from Python against the CLI, to the last digit."""

import json
import math

import numpy as np
import pytest

import contactrb
from conftest import VALUES, cli_error, cli_json, run_cli

POINTS = [0.15, 0.2, 0.2625, 0.3, 0.41, 0.45]


def online_json(model_path, mu, *extra):
    return cli_json("online", "--model", model_path, "--mu", repr(mu), *extra)


def assert_equals_cli(r, j):
    """An OnlineResult equals the JSON of `contactrb online` in every digit."""
    assert r.converged == j["converged"]
    assert r.status == j["status"]
    assert r.iterations == j["iterations"]
    assert r.energy == j["energy"]
    assert r.force == j["contact_force"]
    assert r.coefficients.tolist() == j["u_hat"]
    assert r.multipliers.tolist() == j["lambda_hat"]
    assert r.estimate == j["estimate"]["energy"]
    assert r.estimate_parts == j["estimate"]
    assert r.sizes == j["sizes"]


def without_times(j, top=("model", "snapshots", "snapshots_computed")):
    """A JSON value without its wall times and speed-ups, and without the CLI's own top-level keys
    (the paths of offline.json)."""
    if isinstance(j, dict):
        return {k: without_times(v, ()) for k, v in j.items()
                if k not in top and k not in ("times_s", "time_s", "median_speedup") and not k.endswith("_time_s")}
    if isinstance(j, list):
        return [without_times(v, ()) for v in j]
    return j


@pytest.mark.parametrize("mu", [0.15, 0.2625, 0.41])
def test_solve_equals_cli_online(model, cli_model, mu):
    assert_equals_cli(model.solve(mu), online_json(cli_model, mu))


def test_solve_with_sizes_and_settings_equals_cli(model, cli_model):
    N = model.sizes["N"] - 1
    r = model.solve(0.33, N=N, alpha=0.5, tol=1e-6, start="zero")
    assert_equals_cli(r, online_json(cli_model, 0.33, "--n", N, "--alpha", 0.5, "--tol", 1e-6, "--start", "zero"))


def test_solve_many_equals_cli_batch_and_a_loop_of_solve(model, cli_model, tmp_path):
    batch = tmp_path / "batch.txt"
    batch.write_text("".join(f"{mu!r}\n" for mu in POINTS))
    lines = [json.loads(line) for line in run_cli("online", "--model", cli_model, "--batch", batch).stdout.splitlines()]
    many = model.solve_many(np.array(POINTS))
    assert many["mu"].shape == (len(POINTS), 1)
    for i, (mu, j) in enumerate(zip(POINTS, lines)):
        assert many["energy"][i] == j["energy"]
        assert many["force"][i] == j["contact_force"]
        assert many["iterations"][i] == j["iterations"]
        assert many["coefficients"][i].tolist() == j["u_hat"]
        assert many["multipliers"][i].tolist() == j["lambda_hat"]
        assert many["u_hat"][i].tolist() == j["u_hat"] and many["lambda_hat"][i].tolist() == j["lambda_hat"]
        assert many["contact_force"][i] == j["contact_force"]
        assert many["estimate"][i] == j["estimate"]["energy"]
        assert contactrb.STATUS[many["status"][i]] == j["status"]
        assert bool(many["converged"][i]) == j["converged"]
        r = model.solve(mu)  # the same solver, one query at a time
        assert r.energy == many["energy"][i] and r.force == many["force"][i]
        assert np.array_equal(r.coefficients, many["coefficients"][i])
        assert r.estimate == many["estimate"][i]


def test_offline_from_cli_snapshots_equals_cli_model(cli_snapshots, cli_model, tmp_path):
    snaps = contactrb.Snapshots.load(str(cli_snapshots))
    assert len(snaps) == 5 and snaps.num_failed == 0
    model = contactrb.offline(snaps)
    assert model.sizes == contactrb.Model.load(str(cli_model)).sizes
    # model.report is offline.json but for the CLI's paths and times.
    report = json.loads((cli_model.parent / "offline.json").read_text())
    assert without_times(model.report) == without_times(report)
    assert_equals_cli(model.solve(0.33), online_json(cli_model, 0.33))
    # Saved from Python, answered by the CLI.
    path = tmp_path / "py_model.h5"
    model.save(str(path))
    assert_equals_cli(model.solve(0.27), online_json(path, 0.27))


def test_snapshots_equal_cli_snapshots(cli_snapshots, tmp_path):
    values = np.array([float(v) for v in VALUES.split(",")])
    path = tmp_path / "py_snapshots.h5"
    mine = contactrb.snapshots("hertz-a", values, jobs=2, path=str(path))
    theirs = contactrb.Snapshots.load(str(cli_snapshots))
    assert mine.set_name == theirs.set_name == "custom"
    assert np.array_equal(mine.mu, theirs.mu)
    assert np.array_equal(mine.u, theirs.u)
    assert np.array_equal(mine.multipliers, theirs.multipliers)
    assert np.array_equal(mine.iterations, theirs.iterations)
    again = contactrb.Snapshots.load(str(path))  # the file written from Python reads back equal
    assert np.array_equal(again.u, mine.u)


def test_newton_snapshots_and_offline_equal_cli(tmp_path):
    # solver= reaches the HF solves as the CLI's --solver: the same arrays, the method recorded.
    values = np.array([float(v) for v in VALUES.split(",")])
    cli_file = tmp_path / "newton.h5"
    run_cli("snapshots", "--case", "hertz-a", "--values", VALUES, "--solver", "newton", "-q", "--out", cli_file)
    mine = contactrb.snapshots("hertz-a", values, solver="newton")
    theirs = contactrb.Snapshots.load(str(cli_file))
    assert mine.solver == theirs.solver == "newton"
    assert contactrb.snapshots("hertz-a", values[:1]).solver == "kacanov"  # the default on 2D level 0
    assert np.array_equal(mine.u, theirs.u)
    assert np.array_equal(mine.multipliers, theirs.multipliers)
    assert np.array_equal(mine.iterations, theirs.iterations)
    assert mine.iterations.max() <= 12  # Newton; Kacanov takes 21-25 on hertz-a
    out = tmp_path / "pod" / "model.h5"
    out.parent.mkdir()
    run_cli("offline", "--case", "hertz-a", "--values", VALUES, "--solver", "newton", "-q", "--out", out)
    model = contactrb.offline("hertz-a", set=values, solver="newton")
    assert model.report["snapshot_solver"] == "newton"
    assert_equals_cli(model.solve(0.33), online_json(out, 0.33))
    greedy = contactrb.offline("hertz-a", "greedy", set=values, max_hf=2, solver="newton")
    assert greedy.greedy["snapshots"].solver == "newton"
    with pytest.raises(contactrb.Error, match=r"unknown HF solver 'qr' \(expected newton or kacanov\)"):
        contactrb.snapshots("hertz-a", values, solver="qr")


def test_sequenced_snapshots_equal_cli(tmp_path):
    # sequence= reaches the HF solves as the CLI's --sequence: the same arrays, fewer iterations
    # than the unsequenced cold solves (hertz-a level 2, coarse level 0).
    values = np.array([0.2, 0.3, 0.4])
    cli_file = tmp_path / "sequenced.h5"
    run_cli("snapshots", "--case", "hertz-a", "--level", 2, "--values", "0.2,0.3,0.4", "--solver", "newton",
            "--sequence", 1, "-q", "--out", cli_file)
    mine = contactrb.snapshots("hertz-a", values, level=2, solver="newton", sequence=1)
    theirs = contactrb.Snapshots.load(str(cli_file))
    assert np.array_equal(mine.u, theirs.u)
    assert np.array_equal(mine.iterations, theirs.iterations)
    plain = contactrb.snapshots("hertz-a", values[:1], level=2, solver="newton", sequence=0)
    assert mine.iterations[0] <= plain.iterations[0]
    assert np.abs(mine.u[0] - plain.u[0]).max() < 1e-8 * np.abs(plain.u[0]).max()
    with pytest.raises(contactrb.Error, match=r"sequence must be >= 0, or -1 for automatic \(got -2\)"):
        contactrb.snapshots("hertz-a", values, sequence=-2)


def test_greedy_offline_equals_cli(tmp_path):
    out = tmp_path / "greedy" / "model.h5"
    out.parent.mkdir()
    run_cli("offline", "--greedy", "--case", "hertz-a", "--values", VALUES, "--max-hf", 3, "-q", "--out", out)
    values = np.array([float(v) for v in VALUES.split(",")])
    model = contactrb.offline("hertz-a", "greedy", set=values, max_hf=3)
    g = json.loads((out.parent / "greedy.json").read_text())
    assert model.greedy["status"] == g["status"]
    assert model.greedy["hf_solves"] == g["hf_solves"]
    assert model.greedy["selected"][:, 0].tolist() == g["selected"]
    # greedy.json's content, the points as arrays.
    assert without_times({k: v for k, v in model.greedy.items() if k not in ("selected", "excluded", "snapshots")}) == \
        without_times({k: v for k, v in g.items() if k not in ("selected", "excluded")})
    assert_equals_cli(model.solve(0.33), online_json(out, 0.33))


def test_batched_greedy_offline_equals_cli(tmp_path):
    # greedy_batch=2 on 2 threads against --greedy-batch 2 on one: the same points and model.
    out = tmp_path / "greedy" / "model.h5"
    out.parent.mkdir()
    run_cli("offline", "--greedy", "--case", "hertz-a", "--values", VALUES, "--max-hf", 4, "--greedy-batch", 2,
            "-q", "--out", out)
    values = np.array([float(v) for v in VALUES.split(",")])
    model = contactrb.offline("hertz-a", "greedy", set=values, max_hf=4, greedy_batch=2, jobs=2)
    g = json.loads((out.parent / "greedy.json").read_text())
    assert g["batch"] == 2
    assert model.greedy["hf_solves"] == g["hf_solves"] == 4
    assert [len(step["batch_mu"]) for step in model.greedy["steps"]] == [len(step["batch_mu"]) for step in g["steps"]]
    assert len(model.greedy["steps"][0]["batch_mu"]) == 2
    assert model.greedy["selected"][:, 0].tolist() == g["selected"]
    assert_equals_cli(model.solve(0.33), online_json(out, 0.33))


def test_full_sweep_greedy_equals_cli(tmp_path):
    # greedy_saturation=inf against --greedy-saturation inf: every step solves every point, the
    # same points and model; the default lazy sweep solves fewer after the first step.
    out = tmp_path / "full" / "model.h5"
    out.parent.mkdir()
    run_cli("offline", "--greedy", "--case", "hertz-a", "--values", VALUES, "--max-hf", 3, "--greedy-saturation", "inf",
            "-q", "--out", out)
    values = np.array([float(v) for v in VALUES.split(",")])
    model = contactrb.offline("hertz-a", "greedy", set=values, max_hf=3, greedy_saturation=float("inf"))
    g = json.loads((out.parent / "greedy.json").read_text())
    assert g["saturation"] is None and model.greedy["saturation"] is None  # +inf in JSON
    assert [step["sweep_solves"] for step in g["steps"]] == [len(values)] * len(g["steps"])
    assert model.greedy["selected"][:, 0].tolist() == g["selected"]
    assert_equals_cli(model.solve(0.33), online_json(out, 0.33))
    lazy = contactrb.offline("hertz-a", "greedy", set=values, max_hf=3)
    assert lazy.greedy["saturation"] == 1.0
    assert lazy.greedy["steps"][0]["sweep_solves"] == len(values)
    with pytest.raises(Exception, match="saturation"):
        contactrb.offline("hertz-a", "greedy", set=values, max_hf=3, greedy_saturation=0.5)
    # The row-cone model's start and preconditioner points: every training value by default (fewer
    # than 256), the snapshots only with 0, as --greedy-preconditioner-points.
    assert lazy.training_mu.shape[0] == len(values)
    few = contactrb.offline("hertz-a", "greedy", set=values, max_hf=3, greedy_preconditioner_points=0)
    assert few.training_mu.shape[0] == len(few.greedy["selected"]) < len(values)
    with pytest.raises(Exception, match="preconditioner points"):
        contactrb.offline("hertz-a", "greedy", set=values, max_hf=3, greedy_preconditioner_points=-1)


def test_fields_on_the_hf_mesh_match_the_hf_solution(model):
    # At a training value the reduced solution reproduces the snapshot up to the POD and solver
    # tolerances; the mesh of Omega(mu) is the HF solver's, bitwise.
    hf = contactrb.Case("hertz-a").solve(0.3)
    r = model.solve(0.3)
    f = model.fields(r)
    assert np.array_equal(f["nodes"], hf.nodes)
    assert np.array_equal(f["triangles"], hf.triangles)
    assert f["displacement"].shape == hf.u.shape
    error = np.linalg.norm(f["displacement"] - hf.u) / np.linalg.norm(hf.u)
    assert error < 1e-2, error
    assert f["multipliers"].shape == hf.multipliers.shape


def test_write_fields_equals_cli_online_out(model, cli_model, tmp_path):
    run_cli("online", "--model", cli_model, "--mu", "0.33", "--out", tmp_path / "cli")
    files = model.write_fields(model.solve(0.33), str(tmp_path / "py"))
    for key, name in [("multipliers", "multipliers.csv"), ("vtu", "solution.vtu"), ("contact_vtu", "contact.vtu")]:
        assert open(files[key], "rb").read() == (tmp_path / "cli" / name).read_bytes(), name


def test_evaluate_equals_cli(model, cli_model, tmp_path):
    points = [0.2, 0.33]
    values = tmp_path / "values.txt"
    values.write_text("".join(f"{mu!r}\n" for mu in points))
    run_cli("evaluate", "--model", cli_model, "--set", values, "--repeats", 1, "-q", "--out", tmp_path / "ev")
    j = json.loads((tmp_path / "ev" / "evaluation.json").read_text())
    e = contactrb.evaluate(model, np.array(points), repeats=1)
    s = j["summary"]
    for key in ["e_ener", "e_displ", "e_inter", "e_press", "e_force", "e_peak"]:
        assert e["summary"]["max_" + key] == s[key]["max"], key
        assert e["summary"]["mean_" + key] == s[key]["mean"], key
    # evaluation.json's content but for the CLI's own keys (model path, set name, multiplier files)
    # and the times.
    mine = {k: v for k, v in e.items() if k in j}
    mine["summary"] = {k: v for k, v in e["summary"].items() if k in s}
    theirs = {k: v for k, v in j.items() if k not in ("model", "set", "multipliers")}
    assert without_times(mine) == without_times(theirs)
    assert e["sizes"] == j["sizes"]
    rows = np.genfromtxt(tmp_path / "ev" / "evaluation.csv", delimiter=",", names=True)
    assert np.array_equal(e["energy_rb"], rows["energy_rb"])
    assert np.array_equal(e["energy_hf"], rows["energy_hf"])
    assert np.array_equal(e["estimate"], rows["estimate"])


def test_errors_are_exceptions_with_the_cli_message(model, cli_model, tmp_path):
    message = cli_error("online", "--model", cli_model, "--mu", "7")
    with pytest.raises(contactrb.Error) as e:
        model.solve(7.0)
    assert str(e.value) == message
    missing = tmp_path / "missing.h5"
    message = cli_error("online", "--model", missing, "--mu", "0.3")
    with pytest.raises(contactrb.Error) as e:
        contactrb.Model.load(str(missing))
    assert str(e.value) == message
    with pytest.raises(contactrb.Error, match=r"^point 1: "):
        model.solve_many(np.array([0.3, 7.0]))
    with pytest.raises(contactrb.Error, match="N must be >= 1"):
        model.solve(0.3, N=0)
    with pytest.raises(RuntimeError):  # contactrb.Error is a RuntimeError
        model.solve(0.3, start="nowhere")


def test_non_convergence_is_a_flagged_status(model):
    r = model.solve(0.33, max_iterations=1, tol=1e-14)
    assert not r.converged
    assert r.status == "max_iterations"
    assert r.message
    assert math.isnan(r.estimate) and r.estimate_parts is None
    many = model.solve_many(np.array([0.2, 0.33]), max_iterations=1, tol=1e-14)
    assert not many["converged"].any()
    assert [contactrb.STATUS[c] for c in many["status"]] == ["max_iterations"] * 2
    assert np.isnan(many["estimate"]).all()


def test_solve_many_fields_equal_the_fields_of_solve(model):
    many = model.solve_many(np.array([0.2, 0.41]), fields=True)
    assert many["displacement"].ndim == 3
    for i, mu in enumerate([0.2, 0.41]):
        assert np.array_equal(many["displacement"][i], model.fields(model.solve(mu))["displacement"])


def test_evaluate_at_the_snapshot_points(model, cli_snapshots):
    snaps = contactrb.Snapshots.load(str(cli_snapshots))
    e = contactrb.evaluate(model, snaps, repeats=1)
    assert np.array_equal(e["mu"], snaps.mu)
    assert e["hf_converged"].all() and e["rb_converged"].all()
    # The training points themselves: the model reproduces its snapshots up to its tolerances.
    assert e["summary"]["max_e_displ"] < 1e-2, e["summary"]["max_e_displ"]


def test_solve_many_from_two_threads_equals_serial(model):
    import threading

    points = np.linspace(0.15, 0.45, 200)
    serial = model.solve_many(points)
    out = [None, None]

    def run(k):
        out[k] = model.solve_many(points)

    threads = [threading.Thread(target=run, args=(k,)) for k in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for k in range(2):
        assert np.array_equal(out[k]["energy"], serial["energy"])
        assert np.array_equal(out[k]["coefficients"], serial["coefficients"])


def test_failed_snapshots_are_recorded_and_refused_by_offline():
    snaps = contactrb.snapshots("hertz-a", np.array([0.2, 0.3]), max_iterations=1)
    assert len(snaps) == 2 and snaps.num_failed == 2
    assert not snaps.converged.any()
    assert snaps.status == ["max_iterations", "max_iterations"]
    with pytest.raises(contactrb.Error, match=r"^2 of 2 snapshot solves failed"):
        contactrb.offline(snaps)


def assert_many_equal(a, b):
    """Every array of two solve_many results equal, bit for bit (time_s, a clock reading, aside)."""
    assert set(a) == set(b)
    for key in a:
        if key != "time_s":
            assert a[key].dtype == b[key].dtype and np.array_equal(a[key], b[key], equal_nan=True), key


@pytest.mark.parametrize("jobs", [2, 0])
def test_solve_many_on_threads_equals_one_thread(model, jobs):
    # 200 points: 13 chunks of 16 (online_many.hpp), so both threads answer points, in any order.
    points = np.linspace(0.15, 0.45, 200)
    assert_many_equal(model.solve_many(points, jobs=jobs), model.solve_many(points, jobs=1))
    # Smaller sizes, the relaxed iteration stopped early (flagged statuses, NaN estimates), fields.
    kw = dict(N=model.sizes["N"] - 1, alpha=0.5, tol=1e-8, max_iterations=24)
    one = model.solve_many(points, jobs=1, **kw)
    assert 0 < one["converged"].sum() < len(points) and len(set(one["iterations"])) > 3
    assert np.isnan(one["estimate"][~one["converged"]]).all()
    assert_many_equal(model.solve_many(points, jobs=jobs, **kw), one)
    few = points[::20]
    assert_many_equal(model.solve_many(few, jobs=jobs, fields=True), model.solve_many(few, jobs=1, fields=True))
    empty = model.solve_many(np.zeros((0, 1)), jobs=jobs)
    assert empty["coefficients"].shape == (0, model.sizes["N"])


def test_solve_many_jobs_errors(model):
    with pytest.raises(contactrb.Error, match=r"^jobs must be >= 0 \(0: every hardware thread\), got -1$"):
        model.solve_many(np.array([0.3]), jobs=-1)
    # A refused point: the lowest index and the message of jobs=1, whichever thread met it first.
    points = np.linspace(0.15, 0.45, 200)
    points[[37, 150]] = 7.0
    with pytest.raises(contactrb.Error) as serial:
        model.solve_many(points, jobs=1)
    assert str(serial.value).startswith("point 37: ")
    for jobs in (2, 0):
        with pytest.raises(contactrb.Error) as threaded:
            model.solve_many(points, jobs=jobs)
        assert str(threaded.value) == str(serial.value)
    with pytest.raises(contactrb.Error) as serial:
        model.solve_many(points[:40], jobs=1, N=model.sizes["N"] + 1)
    with pytest.raises(contactrb.Error) as threaded:
        model.solve_many(points[:40], jobs=2, N=model.sizes["N"] + 1)
    assert str(threaded.value) == str(serial.value)


def test_solve_many_on_threads_from_two_python_threads_equals_serial(model):
    import threading

    points = np.linspace(0.15, 0.45, 300)
    serial = model.solve_many(points)
    out = [None, None]

    def run(k):
        out[k] = model.solve_many(points, jobs=2 if k == 0 else 1)

    threads = [threading.Thread(target=run, args=(k,)) for k in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for k in range(2):
        assert_many_equal(out[k], serial)


def test_solve_many_returns_the_peak_pressure_of_each_answer(model):
    points = np.array([0.2, 0.3, 0.4])
    many = model.solve_many(points)
    assert many["peak_pressure"].shape == (3,)
    for i, mu in enumerate(points):
        r = model.solve(mu)
        assert many["peak_pressure"][i] == pytest.approx(np.max(model.fields(r)["multipliers"]), rel=1e-12)
