"""Continuation: the initial state of a point from the final state of the previous point of its branch.

The rule (docs: README "Sweeps"). A continued point runs without the start-up ramps (input and load
``ramp_s = 0``: the drive and the load act in full from t = 0) and starts from the previous point's
final state with
- every mesh deflection and deflection rate kept (the vibration carries over: a branch stays on it);
- every free shaft's speed moved by the change of the operating speed along the rigid-body motion:
  ``w_i = rho_i W_new + (w_i,prev - rho_i,prev W_prev)`` with ``rho_i`` the shaft's speed ratio and ``W``
  the nominal input speed, so the deviation from rigid-body motion (hence every ``delta'``) is kept;
- an input-angle state (torque drive with time-varying stiffness) kept; energy quadratures reset to 0.
A speed-driven input's angle restarts at 0 with the new run (its motion is analytic), so a time-varying
mesh's phase restarts with it. When the varied key changes the state layout (a different number of
states), the point starts cold, like the first point of a branch.

This is the sweep-side copy of ``TorsionalModel.continue_state(y_end_prev, model_prev)`` of the element
model; once that exists, :func:`continue_state` should call it instead.
"""

from __future__ import annotations

import numpy as np

from gearcli.model.layout import Layout
from gearcli.model.spec import ModelSpec

#: ``--set`` overrides of a continued point: no start-up ramps
NO_RAMPS = ("input.ramp_s=0.0", "load.ramp_s=0.0")


def continue_state(y_prev: np.ndarray, spec_prev: ModelSpec, spec_new: ModelSpec) -> np.ndarray | None:
    """``y0`` for ``spec_new`` from the final state ``y_prev`` of ``spec_prev``; None: start cold."""
    lay_prev, lay = Layout.of(spec_prev), Layout.of(spec_new)
    if (lay.n_states != lay_prev.n_states or lay.free_shafts != lay_prev.free_shafts
            or lay.has_theta_state != lay_prev.has_theta_state or y_prev.shape != (lay_prev.n_states,)):
        return None
    y = np.zeros(lay.n_states)
    y[:lay.n_meshes] = y_prev[:lay_prev.n_meshes]
    w_prev, w_new = spec_prev.drive.speed_rad_s, spec_new.drive.speed_rad_s
    rho_prev, rho_new = spec_prev.speed_ratios, spec_new.speed_ratios
    for i in lay.free_shafts:
        i_prev, i_new = lay_prev.i_omega(i), lay.i_omega(i)
        assert i_prev is not None and i_new is not None
        y[i_new] = rho_new[i] * w_new + (y_prev[i_prev] - rho_prev[i] * w_prev)
    if lay.i_theta is not None and lay_prev.i_theta is not None:
        y[lay.i_theta] = y_prev[lay_prev.i_theta]
    return y
