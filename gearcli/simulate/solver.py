"""One wrapper around scipy's ODE solvers: tolerances, output samples, counters, failures.

The loop is the one ``scipy.integrate.solve_ivp`` runs (``OdeSolver.step`` until the end, dense output
evaluated at the requested samples inside each step), written out here so that it can also count
accepted steps, stop a run that exceeds its function-evaluation budget (an explicit method on a
stiff scene would otherwise grind for minutes) and stop at the first non-finite state. Success is
decided from the solver's ``status`` only, never from its message text; failures raise
:class:`~gearcli.errors.SimulationError` with the likely cause and the fix.
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from typing import Optional

import numpy as np
from scipy.integrate import BDF, DOP853, LSODA, RK45, OdeSolver, Radau

from gearcli.errors import SimulationError
from gearcli.model import TorsionalModel

SOLVERS: dict[str, type[OdeSolver]] = {"RK45": RK45, "DOP853": DOP853, "Radau": Radau, "BDF": BDF, "LSODA": LSODA}
IMPLICIT = ("Radau", "BDF", "LSODA")  # take the analytic Jacobian
MAX_NFEV = 5_000_000  # ~30 s of right-hand sides on a 2-core machine; then the run is called off

STATUS_FINISHED, STATUS_FAILED, STATUS_BUDGET, STATUS_NONFINITE = 0, -1, -2, -3


@dataclass(frozen=True)
class Integration:
    t: np.ndarray  # the requested samples
    y: np.ndarray  # (n_states, len(t))
    method: str
    rtol: float
    atol: np.ndarray
    nfev: int
    njev: int
    nlu: int
    steps: int  # accepted steps
    wall_s: float
    status: int  # 0 reached the end; < 0 failed (see STATUS_*)
    message: str
    t_fail: float  # where it stopped


def _solver(model: TorsionalModel, method: str, y0: np.ndarray, t_end: float, rtol: float,
            atol: np.ndarray) -> OdeSolver:
    if method not in SOLVERS:
        raise SimulationError(f"unknown integration method {method!r}; use one of {', '.join(SOLVERS)}")
    extra = {"jac": model.jac} if method in IMPLICIT else {}
    return SOLVERS[method](model.rhs, 0.0, y0, t_end, rtol=rtol, atol=atol, **extra)


def integrate(model: TorsionalModel, t_eval: np.ndarray, method: str, rtol: float, *,
              y0: Optional[np.ndarray] = None, max_nfev: int = MAX_NFEV) -> Integration:
    """Integrate from t = 0 to ``t_eval[-1]`` and sample at ``t_eval`` (ascending, starting at 0).

    Never raises on a solver failure: the returned ``status`` says what happened and ``y`` holds
    the samples reached (the rest NaN); :func:`check` turns a failure into an error.
    """
    y0 = model.initial_state() if y0 is None else np.asarray(y0, dtype=float)
    atol = model.atol(rtol)
    out = np.full((y0.size, t_eval.size), np.nan)
    t0 = time.perf_counter()
    solver = _solver(model, method, y0, float(t_eval[-1]), rtol, atol)
    out[:, t_eval <= 0.0] = y0[:, None]
    done = int(np.searchsorted(t_eval, 0.0, side="right"))
    steps, status, message = 0, STATUS_FINISHED, "reached the end of the run"
    while solver.status == "running":
        msg = solver.step()
        if solver.status == "failed":
            status, message = STATUS_FAILED, str(msg)
            break
        steps += 1
        if not np.all(np.isfinite(solver.y)):
            status, message = STATUS_NONFINITE, "the state became non-finite"
            break
        upto = int(np.searchsorted(t_eval, solver.t, side="right"))
        if upto > done:
            out[:, done:upto] = solver.dense_output()(t_eval[done:upto]).reshape(y0.size, -1)
            done = upto
        if solver.nfev > max_nfev:
            status, message = STATUS_BUDGET, f"more than {max_nfev} right-hand-side evaluations"
            break
    wall = time.perf_counter() - t0
    return Integration(t_eval, out, method, rtol, atol, int(solver.nfev), int(solver.njev), int(solver.nlu),
                       steps, wall, status, message, float(solver.t))
