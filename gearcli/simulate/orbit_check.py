"""The error estimate of a periodic steady state found by shooting: the orbit found again at a tighter tolerance.

A fixed window's statistics are checked by a second integration of the same samples (:mod:`gearcli.simulate.estimate`).
A periodic orbit's error is not that of one period integrated from its start: the start itself is the fixed point of
a period map the solver computed at the run's tolerance, and the map's error is amplified by ``(I - M)^-1`` near a
resonance (a mode of damping ratio zeta resonant with the period: ~1 / (2 pi zeta)). So the check finds the orbit
again: one full Newton step on the period map at ``rtol / 10`` (:func:`gearcli.simulate.estimate.tight_rtol`) from
the orbit found, then damped Newton to its own test, sampled on the same grid (two or three periods with the
variational equations). The step is taken even where the orbit already passes the tight test: that test bounds the
drift over a period, ``(M - I) dx``, which a resonant orbit keeps small for a start ``dx`` 1 / (1 - |mu|) times larger
(Radau at rtol 1e-6 on the oscillator below: its orbit passed the rtol 1e-7 test at once, 2e-5 estimated, 8e-4
true). Each statistic's error is ``tight_scale`` x the difference over the statistics period, judged and
warned as a window's (``statistics_unresolved``, ``error_estimate``, ``solver.check_pass``).

A linear single-DOF mesh oscillator forced by its transmission error at resonance (damping ratio 1e-3, the F_t
amplitude 50x the mean) came out 4.4e-3 of the mean off its closed form in min and max at DOP853 rtol 1e-6, with no
estimate and no warning (tests/simulate/test_periodic_orbit_check.py). Brute-force results (a torque drive, Newton
failed) and the equilibrium keep no estimate: they are a converged repetition of the motion, or exact.
"""

from __future__ import annotations

import time

import numpy as np

from gearcli.model import TorsionalModel
from gearcli.model.outputs import mesh_line_forces, tooth_forces
from gearcli.simulate import estimate
from gearcli.simulate import periodic as pr
from gearcli.simulate.solver import STATUS_FAILED, STATUS_FINISHED, Integration


def applies(steady) -> bool:
    """Whether a periodic result has an orbit the check can find again (shooting, converged)."""
    return getattr(steady, "mode", "") == "periodic" and getattr(steady, "method", "") == "shooting" \
        and bool(getattr(steady, "converged", False))


def check_pass(model: TorsionalModel, run: Integration, window: tuple[float, float], period_s: float,
               fastest_rad_s: float, max_nfev: int) -> estimate.CheckPass:
    """The orbit of ``run`` (its samples from ``window[0]`` to its end: the statistics periods, whole) found again at
    the tight tolerance, and every stage's error estimate over the statistics period (module text)."""
    # lazy: start-up time of a fixed window's run (the shooting is imported by a periodic run only)
    from gearcli.simulate.shooting import Ledger, _newton, _Shooter, newton_step

    t0 = time.perf_counter()
    lay = model.layout
    i0 = int(np.searchsorted(run.t, window[0] - 1e-12 * max(1.0, abs(window[0]))))
    t = run.t[i0:]
    rtol = estimate.tight_rtol(run.rtol)
    scale = estimate.tight_scale(run.rtol, rtol)
    atol = np.broadcast_to(np.asarray(model.atol(rtol), dtype=float), run.y[:, 0].shape)
    sh = _Shooter(model, run.method, rtol, atol, pr.poincare_atol(lay, atol, rtol, fastest_rad_s), float(t[0]),
                  float(t[-1] - t[0]), t.size - 1, run.engine, max_nfev, Ledger(), period_s=period_s)
    sh.parts = []  # (the periods' counters: the check's own)
    y = np.array(run.y[:, i0], dtype=float)
    first = sh.shot(y, True)  # one full Newton step at the tight tolerance, whatever the residual (module text) ...
    if first is not None and first.M is not None:
        dx = newton_step(first.M, first.run.y[:sh.d, -1] - first.x, sh.constraints)
        if dx is not None:
            y[:sh.d] = first.x + dx
    found, why = _newton(sh, y, cap=10 ** 9)  # ... then Newton's own test
    if found is None:
        return estimate.CheckPass(rtol, float(t[0]), scale, sh.used, 0, 0, time.perf_counter() - t0, STATUS_FAILED,
                                  f"the orbit was not found again at rtol {rtol:g}: {why}", ())
    fine = found[0].run
    ours, theirs = mesh_line_forces(lay, t, run.y[:, i0:]), mesh_line_forces(lay, fine.t, fine.y)
    floors = estimate.force_floors_N(model, run.rtol)
    errors = tuple(estimate.stage_error(k, t[:-1], tooth_forces(lay, k, ours[k])[0][:-1],
                                        tooth_forces(lay, k, theirs[k])[0][:-1], m.static_tangential_N, run.rtol,
                                        scale, floor)
                   for (k, m), floor in zip(enumerate(model.spec.meshes), floors, strict=True))
    errors = _over_planets(model, errors, (t, run.y[:, i0:]), (fine.t, fine.y), run.rtol, scale, floors)
    return estimate.CheckPass(rtol, float(t[0]), scale, sh.used, sum(int(p.njev) for p in sh.parts),
                              sum(int(p.steps) for p in sh.parts),
                              time.perf_counter() - t0, STATUS_FINISHED, "", errors)


def _over_planets(model: TorsionalModel, errors: tuple, ours: tuple, theirs: tuple, rtol: float, scale: float,
                  floors: list[float]) -> tuple:
    """``errors`` with each planetary stage's taken over every planet's sun and ring mesh, as a fixed window's check
    does (:func:`gearcli.simulate.estimate.over_planets`): the stage's channels are planet 1's sun mesh only, and on a
    shot orbit of 4 planets with position errors (DOP853, rtol 3e-4) planet 2's sun-mesh max, the stage's dynamic
    factor, was 1.7e-2 off and its ring-mesh max 2.9e-2, the stage "resolved"
    (tests/extreme/test_planet_ring_estimate.py).
    ``ours``, ``theirs``: (sample times, states) of the run's statistics periods and of the orbit found again, whose
    closing sample (the next period's first) is left out as in the stages' estimate."""
    def meshes(gear: str, side: tuple) -> dict:
        return {k: [f[:-1] for f in fs] for k, fs in estimate.planet_suns(model, side[0], side[1], gear).items()}

    suns = meshes("sun", ours)
    if not suns:
        return errors
    tw = ours[0][:-1]
    return estimate.over_planets(model, errors, suns, meshes("sun", theirs), tw, tw.size, rtol, scale, floors,
                                 (meshes("ring", ours), meshes("ring", theirs)))
