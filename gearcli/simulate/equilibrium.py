"""The steady state of an unexcited scene, found directly: its equilibrium.

A scene that nothing excites (no mesh whose stiffness varies in time or with a transmission-error or stiffness
harmonic, no torque ripple, no load fluctuation: :func:`gearcli.simulate.periodic.scene_period` finds no
excitation) and whose input speed is prescribed settles, past the ramps, into rest in the turning frame: every
deflection constant, every free body at its steady speed. That state is a root of the dynamic states' own
equations, ``f(t, x) = 0`` at any ``t`` past the ramps (the equations no longer depend on ``t`` there). Where the
periodic search would integrate period after period of a slowly decaying start-up and shoot on the period map
with the variational equations (a lightly damped drivetrain: 10-20 periods of ``1 + d`` times the work each),
the root is found by Newton's method on ``f`` with the model's analytic Jacobian (its ``d x d`` dynamic block),
from the motion's own state at the end of the ramps:

- the step ``J dx = -f`` is damped: halved at most :data:`HALVINGS` times until the next step, measured with the
  same ``J`` (``J dx' = -f(x + lambda dx)``, in units of the tolerance), is shorter than this one (Deuflhard's
  natural monotonicity test: the distance to the root, which the drift ``|f_i| T`` is not where the masses are
  far apart: on configs/extreme/unequal_inertias.toml a 1e-6 kg m^2 shaft turns a 0.1 % force error of a full step
  into a drift 80x larger, and the drift test halved every step until Newton gave up);
- closed planet loops make combinations of deflections constants of the motion (``J`` singular, exactly
  :func:`gearcli.simulate.shooting.structural_unit_multipliers` of them): the step leaves them where the motion
  put them (it solves ``[J; C^T] dx = [-f; 0]``, ``C`` the left null space of ``J``);
- converged when the step is below :data:`STEP_CONVERGED` of the boundary tolerance, at most
  :data:`MAX_STEPS` steps.

The root is the steady state when it is one: its drift over one period (``|f_i| T`` in units of the boundary
tolerance, :func:`gearcli.simulate.periodic.boundary_residual`'s scale) at most 1, the test a periodic state
passes, and stable. Its stability is that of the linearisation: the eigenvalues ``lambda`` of ``J`` (the
structural zeros left out), reported as the Floquet multipliers over the period, ``exp(lambda T)`` (the eigenvalues
of the linearised motion's monodromy ``expm(J T)``, without forming it). Its statistics period is exact
(:func:`steady_period`): the dynamic states constant, the work quadratures growing at their constant rates; an
integration from it would add only the method's own noise. An unstable root (the motion leaves it: an orbit may
be the steady state then), a Newton that does not converge (a contact lost at the root: ``J`` jumps across the
backlash), or a right-hand side replaced in Python (no Jacobian) leaves the search to the shooting. A settled
run takes the root only where the motion settles into it (:func:`gearcli.simulate.settle.reached`: contracting by
more than 1e-6 per period; an undamped scene's root is not).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from gearcli import engine
from gearcli.core.records import record
from gearcli.model.outputs import Sampled, sample
from gearcli.simulate import periodic as pr
from gearcli.simulate.solver import _packed

MAX_STEPS = 25  # Newton steps
HALVINGS = 4  # step halvings of the damped step
STEP_CONVERGED = 1e-3  # the last step, in units of the boundary tolerance


def applies(model) -> bool:
    """Whether the scene's steady state is an equilibrium this module can find: a prescribed input speed, no
    excitation, and the generated equations (whose analytic Jacobian Newton uses)."""
    lay = model.layout
    return bool(lay.speed_drive and not pr.scene_period(lay).excited and getattr(model, "generated", True))


def _constraints(J: np.ndarray, structural: int) -> np.ndarray:
    """``C^T``: the ``structural`` left null vectors of ``J`` (rows), the deflection combinations the motion keeps."""
    if structural <= 0:
        return np.zeros((0, J.shape[0]))
    u, _, _ = np.linalg.svd(J)
    return u[:, -structural:].T


def _step(J: np.ndarray, f: np.ndarray, C: np.ndarray) -> np.ndarray | None:
    try:
        if C.shape[0] == 0:
            dx = np.linalg.solve(J, -f)
        else:
            dx = np.linalg.lstsq(np.vstack([J, C]), np.concatenate([-f, np.zeros(C.shape[0])]), rcond=None)[0]
    except np.linalg.LinAlgError:
        return None
    return dx if np.all(np.isfinite(dx)) else None


@record
class Root:
    """The equilibrium: the full state (the quadratures as given), the Jacobian's dynamic block there, the
    right-hand side there (the quadratures' rates; the dynamic states' drift), the drift over one period in
    units of the boundary tolerance, and the Newton steps taken."""

    y: np.ndarray
    J: np.ndarray
    rates: np.ndarray
    drift: float
    steps: int


def _functions(model, engine_name: str):
    """``rhs(t, y)`` and ``jac(t, y)`` of the engine the run integrates on: the compiled kernel's own evaluations of
    the model's arrays (the generated Python's terms in the same order, and no Python to generate for a sweep
    point), or the generated Python's."""
    if engine_name != "compiled":
        return model.rhs, model.jac
    evaluate, evaluate_jacobian = engine.point_functions()
    arrays = _packed(model)  # the kernel's packed model, the same the run-up's integration read (packed once)
    return (lambda t, y: evaluate(arrays, float(t), np.ascontiguousarray(y, dtype=float)),
            lambda t, y: evaluate_jacobian(arrays, float(t), np.ascontiguousarray(y, dtype=float)))


def root(model, t: float, y: np.ndarray, rtol: float, patol: np.ndarray, period_s: float,
         structural: int, engine_name: str = "python") -> Root | None:
    """The equilibrium (:class:`Root`) from the state ``y`` at ``t`` past the ramps, with the equations of
    ``engine_name``; None when Newton does not converge (module text)."""
    d = model.layout.state.n_mechanical
    y = np.array(y, dtype=float)
    rhs, jac = _functions(model, engine_name)

    def drift(state: np.ndarray) -> tuple[np.ndarray, float]:
        """The right-hand side at ``state`` and its dynamic states' drift over one period (tolerance units)."""
        rates = np.asarray(rhs(t, state), dtype=float)
        scale = rtol * np.abs(state[:d]) + patol
        return rates, float(np.max(np.abs(rates[:d]) * period_s / scale)) if d else 0.0

    def length(dx: np.ndarray, state: np.ndarray) -> float:
        """A step's length in units of the tolerance at ``state``."""
        return float(np.max(np.abs(dx) / (rtol * np.abs(state[:d]) + patol))) if d else 0.0

    rates = np.asarray(rhs(t, y), dtype=float)
    for n in range(1, MAX_STEPS + 1):
        J = np.asarray(jac(t, y), dtype=float)[:d, :d]
        C = _constraints(J, structural)
        dx = _step(J, rates[:d], C)
        if dx is None:
            return None
        size = length(dx, y)
        if size <= STEP_CONVERGED:  # the full step is below the tolerance's resolution: the root
            y = y.copy()
            y[:d] += dx
            rates, merit = drift(y)
            return Root(y, np.asarray(jac(t, y), dtype=float)[:d, :d], rates, merit, n)
        lam = 1.0
        for _ in range(HALVINGS + 1):
            trial = y.copy()
            trial[:d] += lam * dx
            r_t = np.asarray(rhs(t, trial), dtype=float)
            following = _step(J, r_t[:d], C) if np.all(np.isfinite(r_t[:d])) else None
            if following is not None and length(following, trial) < size:  # closer to the root (module text)
                break
            lam *= 0.5
        else:
            return None
        y, rates = trial, r_t
    return None


def exponents(J: np.ndarray, period_s: float) -> np.ndarray:
    """``lambda T`` of the eigenvalues ``lambda`` of ``J``: their ``exp`` are the Floquet multipliers, the eigenvalues
    of ``expm(J T)``, the monodromy of the motion linearised at the equilibrium over one period."""
    return np.linalg.eigvals(J) * period_s if J.size else np.zeros(0, complex)


def steady_period(first, rates: np.ndarray, y_eq: np.ndarray, t0: float, period_s: float, samples: int,
                  layout):
    """The statistics period at the equilibrium, exactly: every dynamic state constant at ``y_eq``, every work
    quadrature growing at its constant rate from 0 (the period's own work), sampled on the statistics grid. An
    integration from the equilibrium would add the method's own noise and nothing else (an explicit method at a
    rest point takes steps at its stability limit: on the lightly damped seed DOP853 at rtol 1e-6 puts ~2 % of
    the static force into the deflections over a period)."""
    grid = t0 + period_s * np.arange(samples + 1) / samples
    y = np.repeat(np.array(y_eq, dtype=float)[:, None], grid.size, axis=1)
    q = layout.state.quadratures
    y[q] = np.asarray(rates, dtype=float)[q, None] * (grid - t0)[None, :]
    return replace(first, t=grid, y=y, nfev=0, njev=0, nlu=0, steps=0, wall_s=0.0, t_fail=float(grid[-1]))


def sampled(layout, t: np.ndarray, Y: np.ndarray, start: int, *, torques: bool = True, arrays=None) -> Sampled:
    """:func:`gearcli.model.outputs.sample` of ``(t, Y)`` whose dynamic states are one constant state from sample
    ``start`` on (the equilibrium's statistics period, :func:`steady_period`), the same numbers with the constant
    part sampled once: every channel is a function of its own sample's state, speeds and the drive's and load's
    ramps, which are constant past the ramps, so the sample at ``start`` repeated is what sampling each would give.
    A scene whose mesh phases advance with the angles (or any other case) is sampled whole. ``torques=False``:
    without the input and load torques; ``arrays``: the layout's ``Layout.arrays`` where the caller has them
    (both ``sample``'s)."""
    d = layout.state.n_mechanical
    n = t.size - start - 1
    if (n < 1 or start < 0 or not layout.speed_drive or layout.needs_angles or layout.fluctuation
            or t[start] < max(layout.drive.ramp_s, layout.load.ramp_s)
            or Y.shape[1] != t.size or not bool((Y[:d, start:] == Y[:d, start:start + 1]).all())):
        return sample(layout, t, Y, torques=torques, arrays=arrays)
    # the balance reads the stored energy from start
    return sample(layout, t, Y, torques=torques, energy_from=start, constant_from=start, arrays=arrays)


__all__ = ["applies", "exponents", "root", "sampled", "steady_period"]
