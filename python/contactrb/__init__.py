"""contactrb: reduced-basis models of 2-D elastic frictionless contact (docs/python.md).

The workflow of the command line, from Python::

    import contactrb
    case = contactrb.Case("hertz-a")               # or a TOML case file
    hf = case.solve(1.01)                          # high-fidelity solve: hf.u, hf.energy, ...
    snaps = contactrb.snapshots(case, "training", jobs=2)
    model = contactrb.offline(snaps)               # POD; method="greedy" takes a case
    model.save("model.h5"); model = contactrb.Model.load("model.h5")
    r = model.solve(1.01)                          # r.coefficients, r.energy, r.force, r.estimate
    batch = model.solve_many(numpy.linspace(0.9, 1.1, 100))   # dict of numpy arrays
    f = model.fields(r)                            # displacement on the HF mesh
    table = contactrb.evaluate(model, "verification")

Every contactrb error is raised as contactrb.Error (a RuntimeError) with the message the
command line prints; non-convergence is a status (converged, status), never an exception.
"""

try:
    from . import _contactrb  # noqa: F401
except ImportError as _missing:
    import os as _os

    raise ImportError(
        "contactrb: the compiled part of the module (_contactrb) is not in "
        + _os.path.dirname(_os.path.abspath(__file__))
        + ": build it with `cmake --build build --target contactrb_python` "
        "(./scripts/demo.sh and ./scripts/test.sh build it too; docs/python.md)"
    ) from _missing

from ._contactrb import (  # noqa: F401,E402
    STATUS,
    Case,
    Error,
    HFResult,
    Model,
    OnlineResult,
    Parameter,
    Snapshots,
    __version__,
    case_summaries,
    cases,
    evaluate,
    offline,
    snapshots,
)

Error.__module__ = "contactrb"  # tracebacks say contactrb.Error

__all__ = [
    "STATUS",
    "Case",
    "Error",
    "HFResult",
    "Model",
    "OnlineResult",
    "Parameter",
    "Snapshots",
    "case_summaries",
    "cases",
    "evaluate",
    "offline",
    "snapshots",
]
