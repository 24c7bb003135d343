"""The periodic steady state by shooting: Newton's method on the period map, Floquet multipliers.

The period map. Past the ramps the scene is T-periodic in time (:mod:`gearcli.simulate.periodic` finds T,
the common period of its excitations). Its dynamic states ``x`` (every connector deflection, every free
body's speed: what the brute-force search compares at the period boundaries; never the growing input
angle or the work quadratures, which do not act back on the motion) at the start of a period map to
``P(x) = x(t0 + k T)`` at its end. A periodic orbit is a fixed point, ``F(x) = P(x) - x = 0``.

Newton's method. ``F'(x) = M - I`` with the monodromy matrix ``M = dP/dx``: the solution at ``t0 + kT`` of
the variational equations ``Phi' = J(t, y) Phi``, ``Phi(t0) = I``, integrated beside the state with the
model's analytic Jacobian ``J`` (its dynamic block: the quadratures do not act back). Where the variational
equations are unavailable (a right-hand side replaced in Python, which has no Jacobian to go with it) the
columns of ``M`` are finite differences of the map, one extra period per state. The step
``dx = -(M - I)^-1 F`` is damped: halved (at most :data:`HALVINGS` times) until the residual decreases. Closed
loops keep combinations of deflections constant (:func:`structural_constraints`): the step keeps them too.

The residual is measured as the brute-force search measures it, ``max_i |F_i| / (rtol |x_i| + atol_i)``
with the boundary comparison's absolute tolerances (:func:`gearcli.simulate.periodic.poincare_atol`):
converged at 1. The statistics come from the converged period's own integration (sampled finely), so
the converged iterate costs no extra period.

Entering the basin. A few brute-force periods first (:data:`PREAMBLE_COLD` after the ramps; none when a sweep
continues from the previous point's orbit: natural continuation, Newton starts from that orbit). When Newton
does not converge within :data:`MAX_NEWTON` iterations, the damped step cannot reduce the residual, or the orbit
it finds is unstable (a continuation past a fold lands on the middle, unstable branch; the motion does not stay
there), :data:`RETRY_PERIODS` more brute-force periods are integrated from the last state reached by the
motion and Newton starts again, :data:`RETRIES` times; after that the run goes back to the brute-force
search and says why (impacts that change the map faster than Newton can follow, grazing contacts, chaos). A
period-1 orbit that is unstable through a real multiplier below -1 (a period doubling) is followed by Newton
on the map over 2 T from the same state. A Newton candidate is no state of the motion: the energy balance is
that of the statistics period alone, and a candidate whose run fails is Newton's failure, not the run's.

Floquet multipliers. The eigenvalues of ``M`` at the orbit: the orbit is stable when they all lie inside
the unit circle. A real multiplier near +1 (within :data:`NEAR`) means a fold nearby (the branch turns
back: a jump); near -1 a period doubling. A complex pair near the unit circle is not classified: a lightly
damped slow mode puts one there without any bifurcation (the conveyor's drum mode: 0.989 per period); the
spectral radius says how close it is. For a linear system ``y' = A y + f(t)`` the multipliers are
``exp(lambda T)`` of the eigenvalues ``lambda`` of ``A`` (tests/unit/test_shooting.py checks it). Where the
Jacobian is the same all along the orbit (the orbit stays where the equations are linear: a linear mesh without
backlash forced by its transmission error; an equilibrium), only a real ``lambda`` can put a multiplier at +1 (a
fold: a real eigenvalue crossing zero); a complex pair ``exp(lambda T)`` near +1 or -1 is a lightly damped mode
whose damped frequency is a whole multiple of the excitation frequency (near -1: an odd multiple of half of it), a
resonance with one response and no bifurcation (a linear oscillator at resonance with 1 % damping,
multipliers 0.939 +- 0.0002i, was called a fold "the response may jump to another branch":
tests/simulate/test_linear_resonance_no_fold.py).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from gearcli.core.memo import remember
from gearcli.core.records import record
from gearcli.simulate import equilibrium as eq
from gearcli.simulate import periodic as pr
from gearcli.simulate.periodic import CONVERGED, PeriodicRun, _joined, boundary_residual, scene_period
from gearcli.simulate.results import SteadyState
from gearcli.simulate.settle import NEUTRAL
from gearcli.simulate.solver import integrate
from gearcli.simulate.stats import window_slice

MAX_NEWTON = 8  # Newton iterations per attempt
HALVINGS = 3  # step halvings of the damped Newton step
RETRIES = 2  # Newton restarts after RETRY_PERIODS more brute-force periods
RETRY_PERIODS = 10
PREAMBLE_COLD = 3  # brute-force periods after the ramps before the first Newton step
PREAMBLE_CONTINUED = 0  # ... when a sweep point starts from the previous point's orbit: Newton from it directly
NEAR = 0.1  # a real multiplier this close to +1 or -1 marks a bifurcation nearby
REAL_EXPONENT = 1e-12  # an eigenvalue lambda T with |Im| below this (relative) is real (LAPACK gives real ones Im 0)
LINEAR_JACOBIAN = 1e-9  # Jacobian entries along an orbit within this of its largest entry: the same Jacobian
JACOBIAN_SAMPLES = 16  # where along the orbit the Jacobian is compared
STABLE_SLACK = 1e-3  # a spectral radius up to 1 + this counts as the unit circle (the monodromy's own error)
VAR_ATOL_FACTOR = 1e3  # monodromy entries held to this x the state's own accuracy (Newton needs ~1e-3)
FALLBACK_NOTE = "shooting did not converge"  # how a fallback's note starts (its warning's test)
FLIP_NOTE = "the period-1 orbit is unstable through a multiplier below -1: shooting over 2 periods"  # a period-2 start
FD_STEP = 1e-3  # finite-difference step, relative to the state's natural scale (its atol / rtol)


def fell_back(steady) -> bool:
    """A periodic state that is the brute-force search the shooting fell back to after failing (its note says why),
    not a search of a scene the shooting leaves to it (a torque drive, excitations without a common period). The
    fallback's note follows the notes of the search before it (:data:`FLIP_NOTE`'s period-2 start among them)."""
    return steady.method == "brute force" and FALLBACK_NOTE in steady.note


def restarts(steady) -> int:
    """How many of a periodic state's Newton starts followed a failed one (more brute-force periods first): its
    ``attempts`` less the first start and less the period-2 start that a converged period-1 orbit's flip makes from
    the same state (:data:`FLIP_NOTE`: no failure, the orbit doubled its period)."""
    return max(0, (steady.attempts or 1) - 1 - (FLIP_NOTE in (steady.note or "")))


@record
class Floquet:
    """The Floquet multipliers of a periodic orbit and what they say."""

    multipliers: tuple[tuple[float, float], ...]  # (re, im), largest modulus first
    spectral_radius: float
    stable: bool
    bifurcation: str  # "none" | "fold" | "period doubling"
    critical: tuple[float, float] | None  # the multiplier that decides it (largest modulus when "none")


def floquet(M: np.ndarray, near: float = NEAR, structural: int = 0) -> Floquet:
    """The multipliers of the monodromy matrix ``M`` (see the module text). ``structural``: how many multipliers
    are exactly 1 by the state's construction (:func:`structural_unit_multipliers`): the ones nearest +1 are
    left out before the orbit is judged."""
    return judged(np.linalg.eigvals(np.asarray(M, dtype=float)) if M.size else np.zeros(0, complex), near, structural)


def judged(mu: np.ndarray, near: float = NEAR, structural: int = 0, exponents: np.ndarray | None = None) -> Floquet:
    """:func:`floquet` from the multipliers ``mu`` themselves. ``exponents``: where the Jacobian is the same all along
    the orbit, ``lambda T`` of its eigenvalues ``lambda`` (the multipliers are their ``exp``): then only the real ones
    are judged for a bifurcation (module text)."""
    if structural > 0:
        mu = np.delete(mu, np.argsort(np.abs(mu - 1.0), kind="stable")[:structural])
    size = np.abs(mu)  # (the moduli once: the order and the spectral radius read them)
    mu = mu[np.argsort(-size, kind="stable")]
    pairs = tuple(zip(mu.real.tolist(), mu.imag.tolist(), strict=True))
    rho = float(size.max()) if mu.size else 0.0
    kind, critical = "none", (pairs[0] if pairs else None)
    best = math.inf
    judge = mu
    if exponents is not None:
        lam = np.asarray(exponents, dtype=complex)
        if structural > 0:
            lam = np.delete(lam, np.argsort(np.abs(np.exp(lam) - 1.0), kind="stable")[:structural])
        judge = np.exp(lam[np.abs(lam.imag) <= REAL_EXPONENT * np.maximum(1.0, np.abs(lam))].real).astype(complex)
    for m in judge:
        real = abs(m.imag) <= near * 0.5
        for name, target in (("fold", 1.0), ("period doubling", -1.0)):
            d = abs(m - target)
            if real and d < near and d < best:
                kind, critical, best = name, (float(m.real), float(m.imag)), d
    return Floquet(pairs, rho, rho <= 1.0 + STABLE_SLACK, kind, critical)


def _rates(layout) -> np.ndarray:
    """``R``: the map from the free bodies' speeds to the connectors' deflection rates."""
    free = list(layout.free_bodies)
    R = np.zeros((layout.n_conn, len(free)))
    col = {b: i for i, b in enumerate(free)}
    for c, x in enumerate(layout.connectors):
        for b, lever in zip(x.bodies, x.levers, strict=True):
            if b in col:
                R[c, col[b]] += lever
    return R


def structural_constraints(layout, structural: int) -> np.ndarray:
    """``C^T`` (``structural`` rows over the dynamic states): the combinations of deflections no free body's speed
    changes, the constants of the motion of closed loops (the left null space of ``R``, zero on the speeds). A
    Newton step on the period map must keep them (``C^T dx = 0``): ``M - I`` is singular along them, and a step
    that moved them (np.linalg.solve on the near-singular matrix did) locks a preload into the loops, an orbit of
    planets fighting each other (+24 kN against -322 kN on a stage whose planets carry 2 kN each), which no motion
    from rest reaches."""
    R = _rates(layout)
    d = layout.state.n_mechanical
    if structural <= 0:
        return np.zeros((0, d))
    u, _, _ = np.linalg.svd(R / (np.max(np.abs(R)) or 1.0))
    C = np.zeros((structural, d))
    C[:, :layout.n_conn] = u[:, -structural:].T
    return C


def structural_unit_multipliers(layout) -> int:
    """How many Floquet multipliers are 1 by construction: the state holds every connector's deflection, and
    where connectors close loops (a planetary stage: each planet's sun and ring mesh, more deflections than the
    free bodies' speeds can move independently) the combinations of deflections no free body's speed changes
    are constants of the motion, each an eigenvalue 1 of the monodromy whatever the orbit. Their number is
    n_conn - rank(R), ``R`` the map from the free bodies' speeds to the deflection rates."""
    R = _rates(layout)
    if R.size == 0:
        return layout.n_conn
    # the rank of this very matrix: a sweep's points that share their chain (its levers) share it, not recomputed
    key = (R.shape, R.tobytes())
    rank = _RANKS.get(key)
    if rank is None:
        scale = np.max(np.abs(R)) or 1.0
        rank = remember(_RANKS, key, int(np.linalg.matrix_rank(R / scale, tol=1e-9)), cap=32)
    return int(layout.n_conn - rank)


_RANKS: dict[tuple[tuple[int, ...], bytes], int] = {}  # rank of R by its exact entries (structural_unit_multipliers)


def structural_note(layout, structural: int) -> str:
    return (f"{structural} multiplier(s) exactly 1 by construction left out (closed loops: {layout.n_conn} "
            f"deflections over {len(layout.free_bodies)} free bodies)")


# ------------------------------------------------------------------------------ variational equations
class Variational:
    """The scene's equations with the variational equations of its ``d`` dynamic states beside them.

    Augmented state ``[y (n) | Phi[:, 0] | Phi[:, 1] | ... | Phi[:, d-1]]``: column k of ``Phi`` is the
    response of the dynamic states to a unit change of dynamic state k at the period's start.
    ``rhs``/``jac`` follow the solver's conventions (:func:`gearcli.simulate.solver.integrate` runs it
    like a model); the Jacobian given to an implicit method is block diagonal (the second derivatives of the
    state's equations in the columns' equations left out: it only steers the method's Newton iteration).
    """

    def __init__(self, model) -> None:
        st = model.layout.state  # [y | Phi]: StateLayout.variational, over its mechanical states
        self.model, self.spec, self.d, self.n, self.phi = model, model.spec, st.n_mechanical, st.n_states, st.variational
        self.layout = model.layout

    def rhs(self, t: float, ya: np.ndarray) -> np.ndarray:
        n, d = self.n, self.d
        y = ya[:n]
        out = np.empty_like(ya)
        out[:n] = self.model.rhs(t, y)
        J = np.asarray(self.model.jac(t, y))[:d, :d]
        phi = ya[self.phi].reshape(d, d, order="F")
        acc = np.zeros((d, d))
        for j in range(d):  # J @ Phi summed in the compiled kernel's order (both engines: the same numbers)
            acc += np.outer(J[:, j], phi[j, :])
        out[self.phi] = acc.reshape(-1, order="F")
        return out

    def jac(self, t: float, ya: np.ndarray) -> np.ndarray:
        n, d = self.n, self.d
        J = np.asarray(self.model.jac(t, ya[:n]))
        out = np.zeros((n + d * d, n + d * d))
        out[:n, :n] = J
        block = J[:d, :d]
        for k in range(d):
            s = n + k * d
            out[s:s + d, s:s + d] = block
        return out


def augmented_start(y: np.ndarray, d: int) -> np.ndarray:
    """``[y | I]``: the state and the identity as the variational equations' start."""
    return np.concatenate([y, np.eye(d).reshape(-1, order="F")])


def augmented_atol(atol: np.ndarray, d: int, rtol: float, factor: float = VAR_ATOL_FACTOR) -> np.ndarray:
    """Absolute tolerances of ``[y | Phi]``: ``Phi[i, k]`` maps a change of state k of its natural size
    ``s_k = atol_k / rtol`` to an error of state i; it is held to ``factor`` x ``atol_i`` for such a change."""
    scale = atol[:d] / rtol
    phi = factor * atol[:d, None] / scale[None, :]
    return np.concatenate([atol, phi.reshape(-1, order="F")])


def monodromy(run_y_end: np.ndarray, state) -> np.ndarray:
    """``Phi`` at the period's end from the augmented state ``[y | Phi]`` (:attr:`StateLayout.variational`)."""
    d = state.n_mechanical
    return np.asarray(run_y_end[state.variational]).reshape(d, d, order="F")


# ------------------------------------------------------------------------------------- the solve
@dataclass
class Ledger:
    """What the shooting spent and found (the summary's numbers)."""

    periods: int = 0  # periods integrated past the ramps, every one (Newton's and the line search's too)
    iterations: int = 0  # Newton steps taken
    attempts: int = 0
    monodromy: str = "variational"  # "variational" | "finite differences"
    notes: list[str] = field(default_factory=list)


@record
class Shot:
    """One period map evaluation: the finely sampled run from ``x`` (all states), its residual, ``M``."""

    run: Any  # gearcli.simulate.solver.Integration, the model's states only
    x: np.ndarray  # dynamic states at the start
    residual: float  # in tolerance units
    M: np.ndarray | None


def newton_step(M: np.ndarray, F: np.ndarray, C: np.ndarray | None = None) -> np.ndarray | None:
    """``dx`` solving ``(M - I) dx = -F``; None when ``M - I`` is singular to working precision. ``C`` (rows
    ``C^T``, :func:`structural_constraints`): the constants of the motion the step keeps, ``[M - I; C^T] dx =
    [-F; 0]`` by least squares (``M - I`` is singular along them, the stacked matrix is not)."""
    A = M - np.eye(M.shape[0])
    try:
        if C is not None and C.shape[0]:
            dx = np.linalg.lstsq(np.vstack([A, C]), np.concatenate([-F, np.zeros(C.shape[0])]), rcond=None)[0]
        else:
            dx = np.linalg.solve(A, -F)
    except np.linalg.LinAlgError:
        return None
    return dx if np.all(np.isfinite(dx)) else None


class _Shooter:
    """One scene's period map at the period start ``t0`` (fixed: the scene is periodic in time, so every
    Newton iterate starts there)."""

    def __init__(self, model, method: str, rtol: float, atol_run: np.ndarray, patol: np.ndarray, t0: float,
                 span_s: float, samples: int, engine: str, max_nfev: int, ledger: Ledger,
                 period_s: float | None = None) -> None:
        lay = model.layout
        self.model, self.method, self.rtol, self.engine, self.ledger = model, method, rtol, engine, ledger
        self.n, self.d = lay.state.n_states, lay.state.n_mechanical
        self.atol, self.patol, self.t0, self.max_nfev = atol_run, patol, t0, max_nfev
        self.grid = t0 + span_s * np.arange(samples + 1) / samples
        self.period_s = span_s if period_s is None else period_s  # the excitation period (the span is k of them)
        self.used = 0
        self.variational = bool(getattr(model, "generated", True))
        self.structural = structural_unit_multipliers(lay)  # closed planet loops: constants of the motion
        self.constraints = structural_constraints(lay, self.structural)  # which Newton's step keeps
        if self.structural:
            ledger.notes.append(structural_note(lay, self.structural))
        if not self.variational:
            ledger.monodromy = "finite differences"

    def residual(self, x_end: np.ndarray, x: np.ndarray) -> float:
        return boundary_residual(x_end, x, self.rtol, self.patol)

    def _run(self, y: np.ndarray, aug: bool, grid: np.ndarray | None = None):
        grid = self.grid if grid is None else grid
        budget = max(1, self.max_nfev - self.used)
        if aug:
            var = Variational(self.model)
            ya, atol = augmented_start(y, self.d), augmented_atol(self.atol, self.d, self.rtol)
            if self.engine == "compiled":
                r = integrate(self.model, grid, self.method, self.rtol, y0=ya, t0=self.t0, atol=atol,
                              max_nfev=budget, watch_energy=False, engine="compiled")
            else:
                r = integrate(var, grid, self.method, self.rtol, y0=ya, t0=self.t0, atol=atol, max_nfev=budget,  # type: ignore[arg-type]
                              watch_energy=False)
        else:
            r = integrate(self.model, grid, self.method, self.rtol, y0=y, t0=self.t0, atol=self.atol,
                          max_nfev=budget, watch_energy=False, engine=self.engine)
        self.used += r.nfev
        self.ledger.periods += round((grid[-1] - grid[0]) / self.period_s)
        self.parts.append(replace(r, t=r.t[:1], y=r.y[:self.n, :1]))  # counters (and a failure's start) only
        return r

    parts: list  # the run's parts, for their counters: each shot's without its samples (memory: n + d^2 rows)

    def shot(self, y: np.ndarray, with_m: bool) -> Shot | None:
        """The period map from the full state ``y`` (its quadratures zeroed: the period's own work);
        None when the run failed (the failed part is the last of ``parts``)."""
        y = np.array(y, dtype=float)
        y[self.model.layout.state.quadratures] = 0.0
        n, d = self.n, self.d
        r = self._run(y, with_m and self.variational)
        if r.status != 0 or not np.all(np.isfinite(r.y[:, -1])):
            return None
        M = None
        if with_m:
            M = monodromy(r.y[:, -1], self.model.layout.state) if self.variational else self._fd(y, r.y[:d, -1])
            if M is None:
                return None
            r = replace(r, y=r.y[:n], atol=r.atol[:n])
        x_end = r.y[:d, -1]
        return Shot(r, y[:d].copy(), self.residual(x_end, y[:d]), M)

    def _fd(self, y: np.ndarray, x_end: np.ndarray) -> np.ndarray | None:
        """Forward differences of the map, column by column (one period each, end point only)."""
        d = self.d
        M = np.empty((d, d))
        scale = self.atol[:d] / self.rtol
        for k in range(d):
            h = FD_STEP * max(scale[k], abs(y[k]))
            yk = y.copy()
            yk[k] += h
            r = self._run(yk, False, np.array([self.grid[0], self.grid[-1]]))
            if r.status != 0 or not np.all(np.isfinite(r.y[:, -1])):
                return None
            M[:, k] = (r.y[:d, -1] - x_end) / h
        return M


def integrate_shooting(model, method: str, rtol: float, *, steps: int, duration_s: float,
                       window_start_s: float | None, y0: np.ndarray | None, max_nfev: int,
                       fastest_rad_s: float = 0.0, engine: str = "python", continued: bool = False,
                       run_up_samples: int | None = None):
    """``steady = "periodic"`` by shooting (see the module text): the run-up, a few brute-force periods,
    damped Newton on the period map, the statistics from the converged period; back to the brute-force
    search (:func:`gearcli.simulate.periodic.search`) where Newton fails. ``continued``: ``y0`` is the
    previous sweep point's orbit (fewer brute-force periods first); ``run_up_samples``: the run-up's samples
    (:func:`gearcli.simulate.periodic.run_up`). Returns a
    :class:`~gearcli.simulate.periodic.PeriodicRun` or the failed part's ``Integration``."""
    lay = model.layout
    period = pr.scene_period(lay)
    T = period.period_s
    first = pr.run_up(model, method, rtol, steps=steps, duration_s=duration_s, window_start_s=window_start_s,
                      y0=y0, max_nfev=max_nfev, engine=engine, samples=run_up_samples)
    if first.status != 0:
        return first
    t_start = float(first.t[-1])
    patol = pr.poincare_atol(lay, first.atol, rtol, fastest_rad_s)
    cap = pr.periods_cap(duration_s, t_start, T)
    ledger = Ledger()
    parts: list = [first]

    def brute(t: float, y: np.ndarray, why: str):
        ledger.notes.append(why)
        done = ledger.periods
        return pr.search(model, method, rtol, parts, t, y, period, patol, steps=steps, cap=max(0, cap - done),
                         max_nfev=max_nfev, used=sum(p.nfev for p in parts), engine=engine, periods_before=done,
                         shooting=ledger, cap_total=cap)

    if not lay.speed_drive:
        return brute(t_start, first.y[:, -1], f"{'a motor' if lay.motor_drive else 'a torque drive'}: the input's "
                     "speed is the motion's own, so the period over which its angle's excitations repeat follows the "
                     "motion's mean speed, which a period map of fixed length does not; brute force, timed by it")
    if cap < 1:
        return brute(t_start, first.y[:, -1], "no whole period fits before simulation.duration_s")
    if not period.exact:  # excitations without a common period: the response is quasi-periodic, no orbit exists
        return brute(t_start, first.y[:, -1], "the excitations have no common period, so the response has no "
                     "periodic orbit: a fixed point of the map over the slowest one's period is no state of the motion "
                     "(it adds free vibration to close the period); brute force")
    y_motion, t_motion = first.y[:, -1], t_start  # the motion's own state (no Newton correction in it)
    if eq.applies(model):  # nothing excites it: the equilibrium, found directly (gearcli.simulate.equilibrium)
        direct = _at_equilibrium(model, rtol, first, parts, period, patol, ledger, steps, cap, engine)
        if direct is not None:
            return direct
    preamble = PREAMBLE_CONTINUED if continued else PREAMBLE_COLD
    why, k, attempt = "", 1, 0
    while attempt <= RETRIES:
        m = min(preamble if attempt == 0 else RETRY_PERIODS, max(0, cap - ledger.periods - 2))
        if m > 0:
            r = integrate(model, t_motion + T * np.arange(m + 1), method, rtol, y0=y_motion, t0=t_motion,
                          max_nfev=max(1, max_nfev - sum(p.nfev for p in parts)), engine=engine)
            parts.append(r)
            ledger.periods += m
            if r.status != 0:
                return pr._joined(parts, r.t[:1], r.y[:, :1], status_from=r)
            y_motion, t_motion = r.y[:, -1], float(r.t[-1])
        preamble = 0
        ledger.attempts += 1
        samples = pr.statistics_grid(lay, T, k, steps)
        shooter = _Shooter(model, method, rtol, first.atol, patol, t_motion, k * T, samples, engine,
                           max(1, max_nfev - sum(p.nfev for p in parts)), ledger, period_s=T)
        shooter.parts = parts
        found, why = _newton(shooter, y_motion, cap)
        if found is None:  # (a Newton candidate is no state of the motion: its run failing is Newton's failure)
            if ledger.periods >= cap:
                break
            attempt += 1
            continue
        shot, fl = found
        if not fl.stable:
            why = (f"the orbit Newton found is unstable (Floquet multiplier of modulus {fl.spectral_radius:.4g}): "
                   "the motion leaves it")
            if k == 1 and _flips(fl):  # a period doubling behind it: the period-2 orbit, from the same state
                k = 2
                ledger.notes.append(FLIP_NOTE)
                continue
            attempt += 1
            continue
        return _result(model, parts, first, shot, fl, period, ledger, samples, cap, k, structural=shooter.structural)
    return brute(t_motion, y_motion, f"{FALLBACK_NOTE} ({why}); brute force from the motion's state")


def _at_equilibrium(model, rtol: float, first, parts: list, period, patol: np.ndarray, ledger: Ledger, steps: int,
                    cap: int, engine: str):
    """The unexcited scene's steady state as its equilibrium (:mod:`gearcli.simulate.equilibrium`), checked over
    one statistics period; None (with the reason in the ledger's notes) where the shooting must take over."""
    lay = model.layout
    T, t0 = period.period_s, float(first.t[-1])
    structural = structural_unit_multipliers(lay)
    found = eq.root(model, t0, first.y[:, -1], rtol, patol, T, structural, engine)
    if found is None:
        ledger.notes.append("no excitation, but Newton on the equations of motion found no equilibrium from the "
                            "state at the end of the ramps; shooting")
        return None
    exponents = eq.exponents(found.J, T)  # J's eigenvalues once: the multipliers are their exp
    fl = judged(np.exp(exponents), structural=structural, exponents=exponents if found.J.size else None)
    if not fl.stable:
        ledger.notes.append(f"no excitation, but the equilibrium is unstable (multiplier of modulus "
                            f"{fl.spectral_radius:.4g} over a period): the motion leaves it; shooting")
        return None
    if found.drift > CONVERGED:  # (Newton's last step is below the tolerance; a drift above it would be a bug)
        ledger.notes.append(f"no excitation, but the state Newton found drifts by {found.drift:.3g} x the tolerance "
                            "over a period; shooting")
        return None
    samples = pr.statistics_grid(lay, T, 1, steps)
    run = eq.steady_period(first, found.rates, found.y, t0, T, samples, lay)
    ledger.iterations, ledger.monodromy = found.steps, "exp(lambda T), lambda the eigenvalues of J at the equilibrium"
    if structural:
        ledger.notes.append(structural_note(lay, structural))
    ledger.notes.append(f"no excitation: the equilibrium, found by Newton on the equations of motion ({found.steps} "
                        "steps), its period exact")
    shot = Shot(run, found.y[:lay.state.n_mechanical].copy(), float(found.drift), None)
    return _result(model, parts, first, shot, fl, period, ledger, samples, cap, 1, "equilibrium", structural=structural)


def _flips(fl: Floquet) -> bool:
    """A real multiplier at or below -1 + NEAR: the orbit lost (or is about to lose) stability by a flip."""
    return any(abs(im) <= NEAR * 0.5 and re <= -1.0 + NEAR for re, im in fl.multipliers)


def _newton(sh: _Shooter, y: np.ndarray, cap: int) -> tuple[tuple[Shot, Floquet] | None, str]:
    """Damped Newton from the full state ``y``: (the converged shot and its multipliers) or (None, why)."""
    shot = sh.shot(y, True)
    if shot is None:
        return None, "a period of the map failed"
    base = np.array(y, dtype=float)
    for _ in range(MAX_NEWTON):
        assert shot.M is not None
        if shot.residual <= CONVERGED:
            return (shot, floquet(shot.M, structural=sh.structural)), ""
        if sh.ledger.periods >= cap:
            return None, f"the periods allowed by simulation.duration_s ({cap}) are used up"
        F = shot.run.y[:sh.d, -1] - shot.x
        dx = newton_step(shot.M, F, sh.constraints)
        if dx is None:
            return None, "M - I is singular (a multiplier at +1)"
        lam, trial = 1.0, None
        for _h in range(HALVINGS + 1):
            cand = base.copy()
            cand[:sh.d] = shot.x + lam * dx
            trial = sh.shot(cand, True)
            if trial is not None and trial.residual < shot.residual:
                break
            trial = None
            lam *= 0.5
        if trial is None:
            return None, f"the damped Newton step did not reduce the residual ({shot.residual:.3g} x the tolerance)"
        sh.ledger.iterations += 1
        shot = trial
        base[:sh.d] = shot.x
    if shot.residual <= CONVERGED:
        assert shot.M is not None
        return (shot, floquet(shot.M, structural=sh.structural)), ""
    return None, f"no convergence in {MAX_NEWTON} Newton steps (residual {shot.residual:.3g} x the tolerance)"


def constant_jacobian(model, run, d: int, samples: int = JACOBIAN_SAMPLES) -> np.ndarray | None:
    """The dynamic block (``d`` states) of the model's Jacobian where it is the same (within
    :data:`LINEAR_JACOBIAN` of its largest entry) at ``samples`` states spread over the orbit ``run``, else None."""
    J0, scale = None, 0.0
    for i in np.unique(np.linspace(0, run.t.size - 1, samples).astype(int)):
        J = np.asarray(model.jac(float(run.t[i]), run.y[:, i]), dtype=float)[:d, :d]
        if not np.all(np.isfinite(J)):
            return None
        if J0 is None:
            J0, scale = J, max(float(np.max(np.abs(J))) if J.size else 0.0, 1e-300)
        elif np.max(np.abs(J - J0)) > LINEAR_JACOBIAN * scale:
            return None
    return J0


def _linear_verdict(model, shot: Shot, fl: Floquet, ledger: Ledger, structural: int) -> Floquet:
    """``fl`` judged again from the Jacobian's eigenvalues where it is the same all along the orbit (module text)."""
    if fl.bifurcation == "none" or shot.M is None or shot.run.t.size < 2:
        return fl
    d = shot.M.shape[0]
    J = constant_jacobian(model, shot.run, d)
    if J is None:
        return fl
    T = float(shot.run.t[-1] - shot.run.t[0])
    again = judged(np.linalg.eigvals(shot.M), structural=structural, exponents=np.linalg.eigvals(J) * T)
    if again.bifurcation != fl.bifurcation:
        ledger.notes.append(f"the Jacobian is the same all along the orbit: its multipliers are exp(lambda T), and the "
                            f"one near {'+1' if fl.bifurcation == 'fold' else '-1'} is a lightly damped mode resonant "
                            "with the excitation (a complex lambda), no bifurcation")
    return again


def _result(model, parts: list, first, shot: Shot, fl: Floquet, period, ledger: Ledger, samples: int, cap: int,
            k: int = 1, method: str = "shooting", *, structural: int):
    """The periodic run of the converged ``shot``; ``structural``: the layout's structural_unit_multipliers."""
    fl = _linear_verdict(model, shot, fl, ledger, structural)
    fine = shot.run
    keep = first.t < fine.t[0]  # the run-up's last state is no sample of the orbit where the orbit starts there
    kept = window_slice(keep)  # (a slice of the leading samples: read in place, the same numbers as the mask's copy)
    joined = _joined(parts, np.concatenate([first.t[kept], fine.t]), np.hstack([first.y[:, kept], fine.y]))
    steady = SteadyState(mode="periodic", period_s=period.period_s, periods_to_converge=ledger.periods,
                         periodicity=f"period-{k}", converged=True, residual=float(shot.residual),
                         period_source=period.source, window_periods=k, samples_per_period=samples // k,
                         cap_periods=cap, method=method, iterations=ledger.iterations, attempts=ledger.attempts,
                         monodromy=ledger.monodromy,
                         multipliers=fl.multipliers, spectral_radius=fl.spectral_radius,  # stable: inside the
                         stable=fl.stable and fl.spectral_radius <= 1.0 + NEUTRAL,  # circle, not STABLE_SLACK's
                         bifurcation=fl.bifurcation, note="; ".join(ledger.notes))
    t = fine.t
    return PeriodicRun(joined, (float(t[0]), float(t[-1])), (float(t[0]), float(t[-2])), steady, period,
                       energy_from=int(np.count_nonzero(keep)))


PRICED_VARIATIONAL_PERIODS = 3  # variational periods a typical solve integrates (two Newton steps and the check)


def priced_nfev(nfev_run: float, layout, duration_s: float, window_start_s: float | None,
                at_rest: bool = False) -> float:
    """``engine = "auto"``'s price of a shooting run, in right-hand-side evaluations of the scene: ``nfev_run``
    (the estimate for a run to ``duration_s``) scaled to the time actually integrated (the run-up, the
    brute-force periods, :data:`PRICED_VARIATIONAL_PERIODS` periods with the variational equations), each
    variational period weighted by ``1 + d``: every evaluation also forms the Jacobian's ``d x d`` block times the
    ``d`` columns of the monodromy. ``at_rest``: the steady state is an equilibrium found directly
    (:mod:`gearcli.simulate.equilibrium`): the run-up alone."""
    T = scene_period(layout).period_s
    d = layout.state.n_mechanical
    t_start = max(layout.drive.ramps_end_s, layout.load.ramp_s, window_start_s or 0.0)
    span = t_start if at_rest else t_start + T * (PREAMBLE_COLD + PRICED_VARIATIONAL_PERIODS * (1 + d))
    return nfev_run * span / max(duration_s, 1e-300)
