"""Why a run did not finish: :func:`check` turns an integration's status into a SimulationError (or RunTooLong)
naming the likely cause and the fix (the stiffness, a tolerance, a contact law, an inertia)."""

from __future__ import annotations

import numpy as np

from gearcli.core.methods import AUTO, EXPLICIT, IMPLICIT_METHOD
from gearcli.errors import RunTooLong, SimulationError
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


def check(run: Integration, choice: Choice, duration_s: float) -> None:
    """Raise SimulationError naming the likely cause and the fix when the run did not finish."""
    if run.status == STATUS_FINISHED:
        if not np.all(np.isfinite(run.y)):
            raise SimulationError(f"{run.method} returned non-finite values; {_stiffness_hint(choice)}")
        return
    where = f"{run.method} stopped at t = {run.t_fail:.4g} s of {duration_s:g} s"
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
        raise SimulationError(f"{where}: the step size collapsed (solver: {run.message}); likely a violent contact "
                              "impact or a discontinuous stiffness — try method = \"Radau\" or a looser rtol")
    raise SimulationError(f"{where}: {run.message}")


def _divergence_hint(choice: Choice, run: Integration) -> str:
    """The fix for a diverging run: an implicit method for a stiff scene, else a tighter tolerance."""
    if run.method in EXPLICIT:
        return _stiffness_hint(choice)
    return (f"tighten simulation.rtol (now {run.rtol:g}, try {run.rtol / 100:g}); if it persists, check the contact "
            f"law of mesh stage {choice.stiffest_mesh + 1} (stiffness, exponent) and the inertias")


def _stiffness_hint(choice: Choice) -> str:
    k = choice.stiffest_mesh
    freqs = choice.at_operating_point.natural_frequencies_Hz
    f = float(freqs[-1]) if freqs.size else 0.0
    if choice.method in EXPLICIT and choice.indicator > STIFFNESS_LIMIT:
        stiff = (f"mesh stage {k + 1} makes the scene stiff (highest mode {f:.3g} Hz, "
                 f"max|λ|·T = {choice.indicator:.3g}, {choice.indicator / STIFFNESS_LIMIT:.2g}x what an explicit "
                 "method affords here)")
        if choice.requested == AUTO:  # auto took the explicit method as the cheaper one, and found none cheaper after
            return (f"{stiff}; {IMPLICIT_METHOD} was predicted to need {choice.predicted_evals[1]:.2g} evaluations: "
                    f"shorten simulation.duration_s, or check the contact law of mesh stage {k + 1} (stiffness, "
                    "exponent) for a unit mistake")
        return f'{stiff}: use method = "{IMPLICIT_METHOD}" (or "auto")'
    return (f"check the contact law of mesh stage {k + 1} (stiffness, exponent) and the inertias; "
            f'try method = "{IMPLICIT_METHOD}" with a tighter rtol')
