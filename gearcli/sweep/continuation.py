"""Continuation: the initial state of a point from the final state of the previous point of its branch.

The rule (docs/sweeps.md). A continued point runs without the start-up ramps (input and load
``ramp_s = 0``: the drive and the load act in full from t = 0) and starts from the previous point's
final state by :meth:`gearcli.model.TorsionalModel.continue_state`: every connector deflection and
deflection rate kept (the vibration carries over, so a branch stays on it), every free body's speed moved
to the new operating speed along the rigid-body motion (its deviation from rigid motion kept), the body
angles kept (a torque drive's input-angle state as it was; a speed drive's analytic angle starts at the
previous run's end angle, :func:`carry_phases`), a load fluctuation's clock going on from the previous
run's end time, energy quadratures reset to 0. Keeping the angles keeps every mesh phase ``z_p theta_p``
(time-varying stiffness, transmission error) and a torque ripple's phase continuous with the vibration
state: restarted at 0, the excitation would jump by an arbitrary phase at every point and
throw the response off its branch. When the varied key changes the chain (another number of bodies or
connectors, another drive), the point starts cold, like the first point of a branch.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from gearcli.core.records import record
from gearcli.model import TorsionalModel
from gearcli.model.spec import ModelSpec
from gearcli.simulate.shooting import fell_back, restarts

#: ``--set`` overrides of a continued point: no start-up ramps
NO_RAMPS = ("input.ramp_s=0.0", "load.ramp_s=0.0")


@record
class Carried:
    """What a point hands on to the next point of its branch: its model, final state and its time."""

    model: TorsionalModel
    state: np.ndarray
    time_s: float


def carry_phases(spec: ModelSpec, prev: Carried) -> ModelSpec:
    """``spec`` (a ModelSpec) going on from the previous run's end: a speed drive's start angle at the
    previous run's end angle (a torque drive's angle is a state, kept by ``continue_state``), the load
    fluctuation's clock at the previous run's end time."""
    prev_spec = prev.model.spec
    if spec.load.fluctuation:
        spec = dataclasses.replace(spec, load=dataclasses.replace(spec.load, clock_s=prev_spec.load.clock_s + prev.time_s))
    if spec.drive.kind != "speed" or prev_spec.drive.kind != "speed":
        return spec
    angle = prev.model.input_angle(prev.time_s)
    return dataclasses.replace(spec, drive=dataclasses.replace(spec.drive, angle_rad=angle))


def continue_state(y_prev: np.ndarray, model_prev: TorsionalModel, model_new: TorsionalModel,
                   t_prev: float | None = None) -> np.ndarray | None:
    """``y0`` for ``model_new`` from the final state ``y_prev`` of ``model_prev`` at its time ``t_prev``
    (None: past its ramps); None: start cold."""
    if y_prev.shape != (model_prev.n_states,) or model_new.n_states != model_prev.n_states:
        return None
    try:
        return model_new.continue_state(y_prev, model_prev, t_prev)
    except ValueError:  # another chain of bodies and connectors
        return None


# ------------------------------------------------------------------------------- jumps and folds
JUMP_CHANGE = 0.3  # a relative change of a stage's DTE rms (or force std) this large between neighbours: a jump
FOLD_BISECTIONS = 10  # halvings of the neighbours' distance after which a step that leaves the branch is a jump
MAX_REFINEMENTS = 6 * FOLD_BISECTIONS  # evaluations spent following a branch towards the next point


RESOLVED = 1e-6  # a vibration below this fraction of its channel's mean is rounding (an equilibrium's: none)
FLIP_NEAR = 0.01  # a branch that ends with a real multiplier this close to -1 (or past it) ends at a period doubling


def on_branch(prev, result) -> bool:
    """Whether ``result`` (a periodic point continued from ``prev``'s orbit) stayed on ``prev``'s branch: its
    shooting converged from the continued orbit at the first start (the period-2 start that a flip of the period-1
    orbit makes from the same state counts as that start: a period doubling does not end the branch), or it is an
    equilibrium found directly, or the motion itself was integrated on from that orbit: a settled window, a
    refinement point close to ``prev``, or the brute-force search of a scene the shooting leaves to it, a torque
    drive or excitations without a common period; not a brute-force search the shooting fell back to after failing from the continued orbit,
    which is how a branch that ends at a fold shows), and no stage's DTE rms (force std when no DTE) changed by
    :data:`JUMP_CHANGE` or more of the larger one, or of :data:`RESOLVED` of the channel's mean where both are
    below it (an equilibrium's rms is rounding)."""
    st = result.steady
    followed = st is not None and (st.mode == "window" and st.settled is True  # integrated on to a settled state
                                   or st.mode == "periodic" and st.method == "brute force"  # the motion, from prev,
                                   and not fell_back(st))  # where no shooting failed on it
    if st is None or not followed and (st.method not in ("shooting", "equilibrium") or restarts(st) > 0):
        return False
    for a, b in zip(prev.stages, result.stages, strict=False):
        (x0, m0), (x1, m1) = _amplitude(a, b), _amplitude(b, a)
        if abs(x1 - x0) > JUMP_CHANGE * max(abs(x0), abs(x1), RESOLVED * max(m0, m1), 1e-300):
            return False
    return True


def has_branch(result) -> bool:
    """Whether a point's steady state is one a branch can be followed from: not a periodic search that found no
    period (a chaotic or quasi-periodic motion, or one still settling, ``converged`` False): there is no orbit whose
    end a bisection could locate, and its statistics are only its last period's."""
    st = result.steady
    return st is not None and not (st.mode == "periodic" and st.converged is False)


def _amplitude(stage, other) -> tuple[float, float]:
    """A stage's vibration measure for :func:`on_branch` and its channel's |mean|: the DTE rms where both results
    have the DTE (``other``: the stage compared with), else the force std."""
    if stage.dte_um is not None and other.dte_um is not None:
        return stage.dte_um.rms, abs(stage.dte_um.mean)
    return stage.tangential_N.std, abs(stage.tangential_N.mean)


REAL = 1e-9  # a Floquet multiplier whose imaginary part is at most this is real


def _multipliers(result) -> tuple:
    """A periodic result's Floquet multipliers as (re, im) pairs; () without them."""
    return result.steady.multipliers if result.steady is not None and result.steady.multipliers else ()


def _top_real(result) -> float | None:
    """The largest real Floquet multiplier of a periodic result; None when its largest-real-part one is complex."""
    mus = _multipliers(result)
    if not mus:
        return None
    re, im = max(mus, key=lambda m: m[0])
    return re if abs(im) <= REAL else None


def _lowest_real(result) -> float | None:
    """The lowest real Floquet multiplier of a periodic result; None without one."""
    return min((re for re, im in _multipliers(result) if abs(im) <= REAL), default=None)


def fold_estimate(v_a: float, mu_a: float, v_b: float, mu_b: float) -> float | None:
    """Where a real multiplier reaches +1, from two points of a branch approaching a fold (saddle-node: the
    distance to the fold goes as (1 - mu)^2, so (1 - mu)^2 is linear in the parameter near it); None when the
    two do not approach +1."""
    a, b = (1.0 - mu_a) ** 2, (1.0 - mu_b) ** 2
    if not (mu_a < mu_b < 1.0) or a == b:
        return None
    return v_b + (v_b - v_a) * b / (a - b)


def jump_note(key: str, v_prev: float, v: float, prev, result, refine=None) -> str:
    """The row's mark when a continued periodic point left its predecessor's branch, or "" when it did not:
    the branch is followed from ``prev`` towards ``v`` by step halving (``refine(value, last)`` evaluates the
    scene at a value, continued along the branch from ``last``; a step that leaves the branch is halved, one that
    stays on it is taken and the next one doubled). Reaching ``v`` on the branch means the neighbours only differed
    by a steep but smooth flank (a sharp linear resonance swept coarsely): no jump. A jump is a step of
    1/2^FOLD_BISECTIONS of the neighbours' distance that still leaves the branch (a smooth response changes less
    and less as the step shrinks, a discontinuity does not); where it ends, the Floquet multipliers say what it is: a
    real one heading to +1 is a fold, located where it reaches +1 (:func:`fold_estimate` from the last two
    points of the branch); a real one at -1 (within :data:`FLIP_NEAR`, or past it within the shooting's slack) a
    period doubling (it was called "not near +1: a non-smooth end", quoting the multiplier of largest real part)."""
    last, last_v, hi = prev, v_prev, v
    before, before_v = None, None
    if refine is not None:
        finest = abs(v - v_prev) / 2 ** FOLD_BISECTIONS * (1 + 1e-9)
        step = 0.5 * (v - v_prev)  # the whole step left the branch (the row itself)
        for _ in range(MAX_REFINEMENTS):
            nxt = v if abs(step) >= abs(v - last_v) else last_v + step
            got = refine(nxt, last)
            if got is not None and on_branch(last, got):
                before, before_v, last, last_v = last, last_v, got, nxt
                if nxt == v:
                    return ""  # followed to the point itself: a smooth flank, not a jump
                step *= 2  # a smooth stretch: longer steps again
            elif abs(nxt - last_v) > finest:
                hi, step = nxt, 0.5 * (nxt - last_v)
            else:
                hi = nxt  # the finest step leaves the branch: it ends here
                break
        else:  # out of refinements: the branch is known to reach last_v, not where it ends
            hi = hi if (hi - last_v) * (v - v_prev) > 0 else v
    mus = _multipliers(last)
    mu = max(mus, key=lambda m: m[0]) if mus else None
    if mu is None:
        fold = ""
    elif abs(mu[1]) <= REAL and mu[0] > 0.5:
        fold = f"; there its Floquet multiplier {mu[0]:.3g} (real) heads to +1: a fold"
        mu_before = _top_real(before) if before is not None else None
        at = fold_estimate(before_v, mu_before, last_v, mu[0]) if mu_before is not None and before_v is not None \
            else None
        if at is not None and min(last_v, hi) - abs(hi - last_v) <= at <= max(last_v, hi) + abs(hi - last_v):
            fold += f", reaching it at {key} = {at:.6g} (extrapolated)"
    elif (flip := min((m for m in mus if abs(m[1]) <= REAL and m[0] < -0.5), default=None)) is not None \
            and flip[0] <= -1.0 + FLIP_NEAR:
        fold = (f"; there its Floquet multiplier {flip[0]:.5g} (real) reaches -1: a period doubling (the orbit of twice "
                "the period takes over)")
        mu_before = _lowest_real(before) if before is not None else None
        at = None if mu_before is None or before_v is None or mu_before == flip[0] \
            else last_v + (last_v - before_v) * (-1.0 - flip[0]) / (flip[0] - mu_before)  # crossing: linear in the key
        if at is not None and min(v_prev, hi) <= at <= max(v_prev, hi):  # the shooting takes an orbit up to 1e-3 past
            fold += f", at {key} = {at:.6g} (interpolated)"
    else:
        fold = (f"; there its largest Floquet multiplier {mu[0]:.3g}{mu[1]:+.3g}i is not near +1: a non-smooth end "
                "(a contact starting to open, impacts) rather than a smooth fold")
    return (f"jump: the branch of the previous point ({key} = {v_prev:g}) ends between {last_v:.8g} and {hi:.8g}"
            f"{fold}")
