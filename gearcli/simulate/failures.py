"""Why a run did not finish: :func:`check` turns an integration's status into a SimulationError (or RunTooLong)
naming the likely cause and the fix (the stiffness, a tolerance, a contact law, an inertia, or a train that ran away:
a drive and load whose balance is unstable, which no integrator setting helps)."""

from __future__ import annotations

import numpy as np

from gearcli.core.methods import AUTO, EXPLICIT, IMPLICIT, IMPLICIT_METHOD
from gearcli.errors import RunTooLong, SimulationError
from gearcli.model.equations import TorsionalModel
from gearcli.simulate.choice import STIFFNESS_LIMIT, Choice
from gearcli.simulate.solver import (
    STATUS_BUDGET,
    STATUS_ENERGY,
    STATUS_FAILED,
    STATUS_FINISHED,
    STATUS_NONFINITE,
    STATUS_PROJECTED,
    Integration,
)

RUNAWAY_FACTOR = 10.0  # a body this many times faster than its nominal speed when the run fails: it ran away


def check(run: Integration, choice: Choice, duration_s: float, model: TorsionalModel | None = None) -> None:
    """Raise SimulationError naming the likely cause and the fix when the run did not finish (with the ``model``,
    a train that ran away before the failure is named as such)."""
    if run.status == STATUS_FINISHED:
        if not np.all(np.isfinite(run.y)):
            raise SimulationError(f"{run.method} returned non-finite values; {_stiffness_hint(choice)}")
        return
    where = f"{run.method} stopped at t = {run.t_fail:.4g} s of {duration_s:g} s"
    away = ran_away(model, run) if model is not None and run.status != STATUS_PROJECTED else None
    if away is not None:
        raise SimulationError(f"{where}: {away}")
    if run.status == STATUS_PROJECTED:
        freqs = choice.at_operating_point.natural_frequencies_Hz
        fastest = f"; its fastest mode is {float(freqs[-1]):.3g} Hz" if freqs.size else ""
        raise RunTooLong(f"{where}: {run.message}{fastest}. Shorten simulation.duration_s, loosen simulation.rtol, "
                         "or check for a tiny inertia on a stiff coupling or mesh (a unit mistake?)")
    if run.status == STATUS_BUDGET:
        if run.method in EXPLICIT:
            raise SimulationError(f"{where}: {run.message}. {_stiffness_hint(choice)}")
        freqs = choice.at_operating_point.natural_frequencies_Hz
        fastest = f" (its fastest mode: {float(freqs[-1]):.3g} Hz)" if freqs.size else ""
        raise SimulationError(f"{where}: {run.message}; the run is too long for its dynamics{fastest} or the contacts "
                              "impact violently — shorten simulation.duration_s, loosen simulation.rtol, or check "
                              "for a tiny inertia on a stiff coupling or mesh (a unit mistake?)")
    if run.status in (STATUS_NONFINITE, STATUS_ENERGY):
        cause = "the solution diverged (non-finite state)" if run.status == STATUS_NONFINITE \
            else "the solution is unstable"
        raise SimulationError(f"{where}: {cause}: {run.message}. {_divergence_hint(choice, run)}")
    if run.status == STATUS_FAILED:
        fix = "a looser rtol" if run.method in IMPLICIT else f'method = "{IMPLICIT_METHOD}" or a looser rtol'
        raise SimulationError(f"{where}: the step size collapsed (solver: {run.message}); likely a violent contact "
                              f"impact or a discontinuous stiffness — try {fix}")
    raise SimulationError(f"{where}: {run.message}")


def ran_away(model: TorsionalModel, run: Integration) -> str | None:
    """Why a failed run failed where a body ran away: at the last sample reached, the free body fastest against its
    nominal speed turned more than :data:`RUNAWAY_FACTOR` times faster (the step size collapses as the speed grows
    without bound: a load that drives the train with a torque growing with speed, a negative ``[load] torque`` with
    ``speed_exponent`` 1 or 2, against a torque drive has no stable balance). None where nothing ran away."""
    lay = model.layout
    reached = np.nonzero(np.all(np.isfinite(run.y), axis=0))[0]
    if reached.size == 0:
        return None
    k = int(reached[-1])
    found = None
    for i, nominal in zip(lay.free_bodies, model.speed_scales_rad_s(), strict=True):
        j = lay.state.omega(i)
        if j is None or nominal <= 0.0:
            continue
        factor = abs(float(run.y[j, k])) / nominal
        if factor > RUNAWAY_FACTOR and (found is None or factor > found[0]):
            found = (factor, i, float(run.y[j, k]), nominal)
    if found is None:
        return None
    factor, i, w, nominal = found
    rpm = 30.0 / np.pi
    return (f"the train ran away: {lay.bodies[i].label} turned at {w * rpm:.4g} rpm at t = {float(run.t[k]):.4g} s, "
            f"{factor:.3g}x its nominal {nominal * rpm:.4g} rpm, and kept accelerating: {_runaway_cause(lay)}; no "
            "integrator setting helps")


def _runaway_cause(lay) -> str:
    """What lets a train run away: under a speed drive (the input held at its speed) the response itself grew without
    bound; under a torque or motor drive, a load that drives the train harder the faster it turns, or torques whose
    signs do not balance."""
    if lay.drive.kind == "speed":  # the drive holds the input: the energy came in through the train's own response
        return ("with the input held at its speed, the train's own response grew without bound, an instability (a "
                "time-varying mesh stiffness or an excitation pumping energy in against too little damping: "
                "[contact] damping, stiffness_harmonics)")
    load = lay.spec.load
    brake = ("the motor's curve does not brake it (beyond its generating breakdown torque)" if lay.drive.kind == "motor"
             else "a torque drive does not brake it")
    if load.torque_Nm < 0.0 and (load.speed_exponent or load.table):
        return (f"the drive does not hold the load: a load that drives the train with a torque growing with speed (a "
                f"negative [load] torque on a speed law) has no stable balance, and {brake}; check the drive's and the "
                "load's torques and their signs")
    return f"the drive does not hold the load ({brake}): check the drive's and the load's torques and their signs"


def _divergence_hint(choice: Choice, run: Integration) -> str:
    """The fix for a diverging run: an implicit method for a stiff scene, else a tighter tolerance."""
    if run.method in EXPLICIT:
        return _stiffness_hint(choice)
    return (f"tighten simulation.rtol (now {run.rtol:g}, try {run.rtol / 100:g}); if it persists, check "
            f"{choice.stiff_element[1]} and the inertias")


def _stiffness_hint(choice: Choice) -> str:
    name, keys = choice.stiff_element
    freqs = choice.at_operating_point.natural_frequencies_Hz
    f = float(freqs[-1]) if freqs.size else 0.0
    if choice.method in EXPLICIT and choice.indicator > STIFFNESS_LIMIT:
        stiff = (f"{name} makes the scene stiff (highest mode {f:.3g} Hz, "
                 f"max|λ|·T = {choice.indicator:.3g}, {choice.indicator / STIFFNESS_LIMIT:.2g}x what an explicit "
                 "method affords here)")
        if choice.requested == AUTO:  # auto took the explicit method as the cheaper one, and found none cheaper after
            return (f"{stiff}; {IMPLICIT_METHOD} was predicted to need {choice.predicted_evals[1]:.2g} evaluations: "
                    f"shorten simulation.duration_s, or check {keys} for a unit mistake")
        return f'{stiff}: use method = "{IMPLICIT_METHOD}" (or "auto")'
    return f'check {keys} and the inertias; try method = "{IMPLICIT_METHOD}" with a tighter rtol'
