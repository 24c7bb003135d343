"""Continuation: the initial state of a point from the final state of the previous point of its branch.

The rule (README "Sweeps"). A continued point runs without the start-up ramps (input and load
``ramp_s = 0``: the drive and the load act in full from t = 0) and starts from the previous point's
final state by :meth:`gearcli.model.TorsionalModel.continue_state`: every connector deflection and
deflection rate kept (the vibration carries over, so a branch stays on it), every free body's speed moved
to the new operating speed along the rigid-body motion (its deviation from rigid motion kept), an
input-angle state (torque drive with time-varying stiffness) kept, energy quadratures reset to 0. A
speed-driven input's angle restarts at 0 with the new run (its motion is analytic), so a time-varying
mesh's phase restarts with it. When the varied key changes the chain (another number of bodies or
connectors, another drive), the point starts cold, like the first point of a branch.
"""

from __future__ import annotations

import numpy as np

#: ``--set`` overrides of a continued point: no start-up ramps
NO_RAMPS = ("input.ramp_s=0.0", "load.ramp_s=0.0")


def continue_state(y_prev: np.ndarray, model_prev, model_new) -> np.ndarray | None:
    """``y0`` for ``model_new`` from the final state ``y_prev`` of ``model_prev``; None: start cold."""
    if y_prev.shape != (model_prev.n_states,) or model_new.n_states != model_prev.n_states:
        return None
    try:
        return model_new.continue_state(y_prev, model_prev)
    except ValueError:  # another chain of bodies and connectors
        return None
