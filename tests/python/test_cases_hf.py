"""Cases and high-fidelity solves from Python against `contactrb cases` and `contactrb solve`."""

import json
import os

import numpy as np
import pytest

import contactrb
from conftest import cli_error, run_cli


def test_cases_are_the_cli_list_without_the_frictional_ones(cli):
    lines = [line for line in run_cli("cases").stdout.splitlines() if line.strip()]
    listed = [line.split()[0] for line in lines if " frictional " not in line]
    assert len(listed) == len(lines) - 2  # cattaneo, cattaneo-3d
    assert contactrb.cases() == listed
    assert set(contactrb.case_summaries()) == set(listed)


def test_case_parameters_and_sets():
    case = contactrb.Case("hertz-a")
    assert case.name == "hertz-a"
    assert case.num_parameters == len(case.parameters) == 1
    p = case.parameters[0]
    assert p.min < p.reference < p.max or p.min <= p.reference <= p.max
    training = case.set("training")
    assert training.ndim == 2 and training.shape[1] == 1
    assert np.all(np.diff(training[:, 0]) > 0)  # strictly increasing (cases::check_points)
    assert np.array_equal(case.sets["training"], training)
    assert np.all((training >= p.min) & (training <= p.max))


def test_hf_solve_equals_cli_to_the_last_digit(cli, tmp_path):
    out = tmp_path / "hf"
    run_cli("solve", "--case", "hertz-a", "--mu", "0.33", "--out", out)
    j = json.loads((out / "solution.json").read_text())
    r = contactrb.Case("hertz-a").solve(0.33)
    assert r.converged and j["converged"]
    assert r.status == j["status"]
    assert r.iterations == j["iterations"]
    assert r.energy == j["energy"]
    assert r.force == j["contact_force"]
    assert r.active_constraints == j["active_constraints"]
    assert r.kkt == j["kkt"]
    assert r.u.shape == (j["n_dofs"] // 2, 2)
    assert len(r.multipliers) == j["n_constraints"]
    # The multipliers as multipliers.csv lists them (shortest round-trip digits).
    rows = np.genfromtxt(out / "multipliers.csv", delimiter=",", names=True)
    assert np.array_equal(rows["pressure"], r.multipliers)


def test_hf_solve_from_a_toml_case_equals_cli(cli, tmp_path):
    src = os.environ.get("CONTACTRB_SOURCE_DIR")
    if not src:
        pytest.skip("CONTACTRB_SOURCE_DIR is not set")
    toml = os.path.join(src, "examples", "hertz-a", "case.toml")
    case = contactrb.Case(toml)
    mu = float(case.reference_mu[0])
    out = tmp_path / "hf"
    run_cli("solve", "--case-file", toml, "--mu", repr(mu), "--out", out)
    j = json.loads((out / "solution.json").read_text())
    r = case.solve(mu)
    assert (r.energy, r.force, r.iterations) == (j["energy"], j["contact_force"], j["iterations"])


def test_unknown_case_raises_the_cli_message(cli):
    message = cli_error("solve", "--case", "no-such-case", "--mu", "0.3", "--out", "unused")
    with pytest.raises(contactrb.Error) as e:
        contactrb.Case("no-such-case")
    assert str(e.value) == message
    assert isinstance(e.value, RuntimeError)


def test_frictional_case_raises_the_cli_message(cli):
    message = cli_error("snapshots", "--case", "cattaneo", "--set", "training", "--out", "unused.h5")
    assert message.startswith("case 'cattaneo' is frictional: only `contactrb solve` handles friction")
    with pytest.raises(contactrb.Error) as e:
        contactrb.Case("cattaneo")
    assert str(e.value) == message


def test_mu_outside_the_domain_raises_the_cli_message(cli, tmp_path):
    message = cli_error("solve", "--case", "hertz-a", "--mu", "7", "--out", tmp_path / "x")
    with pytest.raises(contactrb.Error) as e:
        contactrb.Case("hertz-a").solve(7.0)
    assert str(e.value) == message


def test_hf_non_convergence_is_a_status_not_an_exception():
    r = contactrb.Case("hertz-a").solve(0.3, max_iterations=1)
    assert not r.converged
    assert r.status == "max_iterations"
    assert r.message


def test_an_unbuilt_extension_is_an_import_error_that_says_how_to_build_it(tmp_path):
    # The package as configure leaves it before the build: __init__.py without _contactrb.
    package = tmp_path / "contactrb"
    package.mkdir()
    package.joinpath("__init__.py").write_text(open(contactrb.__file__).read())
    code = "import contactrb"
    import subprocess
    import sys

    r = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, env={"PYTHONPATH": str(tmp_path)},
                       capture_output=True, text=True)
    assert r.returncode != 0
    assert "ImportError: contactrb: the compiled part of the module (_contactrb) is not in" in r.stderr
    assert "cmake --build build --target contactrb_python" in r.stderr
