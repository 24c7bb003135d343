"""Continuation: the initial state of a point from the final state of the previous point of its branch.

The rule (README "Sweeps"). A continued point runs without the start-up ramps (input and load
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
from dataclasses import dataclass

import numpy as np

#: ``--set`` overrides of a continued point: no start-up ramps
NO_RAMPS = ("input.ramp_s=0.0", "load.ramp_s=0.0")


@dataclass(frozen=True)
class Carried:
    """What a point hands on to the next point of its branch: its model, final state and its time."""

    model: object  # gearcli.model.TorsionalModel
    state: np.ndarray
    time_s: float


def carry_phases(spec, prev: Carried):
    """``spec`` (a ModelSpec) going on from the previous run's end: a speed drive's start angle at the
    previous run's end angle (a torque drive's angle is a state, kept by ``continue_state``), the load
    fluctuation's clock at the previous run's end time."""
    prev_spec = prev.model.spec  # type: ignore[attr-defined]
    if spec.load.fluctuation:
        spec = dataclasses.replace(spec, load=dataclasses.replace(spec.load, clock_s=prev_spec.load.clock_s + prev.time_s))
    if spec.drive.kind != "speed" or prev_spec.drive.kind != "speed":
        return spec
    angle = prev.model.input_angle(prev.time_s)  # type: ignore[attr-defined]
    return dataclasses.replace(spec, drive=dataclasses.replace(spec.drive, angle_rad=angle))


def continue_state(y_prev: np.ndarray, model_prev, model_new, t_prev: float | None = None) -> np.ndarray | None:
    """``y0`` for ``model_new`` from the final state ``y_prev`` of ``model_prev`` at its time ``t_prev``
    (None: past its ramps); None: start cold."""
    if y_prev.shape != (model_prev.n_states,) or model_new.n_states != model_prev.n_states:
        return None
    try:
        return model_new.continue_state(y_prev, model_prev, t_prev)
    except ValueError:  # another chain of bodies and connectors
        return None
