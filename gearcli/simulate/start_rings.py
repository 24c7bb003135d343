"""The start's ringing that the output samples cannot see: a mode above their Nyquist frequency that a step at
t = 0 sets swinging (docs/numerics.md, "The run's peak: a start the samples alias").

The run's peak |F_t| of a start from rest is the largest of its samples, with the parabola's estimate of what lies
between them (:func:`gearcli.simulate.sampling.peak_warnings`) and a warning where the samples chatter around it.
Both read the samples: a mode sampled fewer than twice a period shows up in them as a slow, smooth wave at its alias
(:mod:`gearcli.simulate.aliasing`) and its first swings, the start's peak, fall between them unseen. Measured: a
motor started direct on a 23 Hz coupling mode, 600 s sampled every 50 ms, reported a peak of 12,375 N (run-up factor
2.10) at 0.6 s, unwarned, where the start's first swing reaches 15,590 N at 0.021 s (2.65).

What a step sets swinging is the linear step response of the scene's linearisation at full load (the tangents
``modes`` uses, :func:`gearcli.model.modes.modal_analysis`): the torques that act at once at t = 0 (the motor's
torque at standstill with its starting method, a torque drive or a load with ``ramp_s = 0``) as a vector ``tau`` on
the free bodies, the first-order system ``x' = A x + b`` in (angles, speeds) with ``b = (0, tau / J)``, and its
eigen-decomposition ``A = V diag(lambda) V^-1``: from rest, each oscillating pair adds
``2 Re(v (V^-1 b) e^(lambda t) / lambda)`` to the state, so a connector force ``g . x`` (``g`` its tangent
stiffness and damping times its levers) swings with ``2 |g . v (V^-1 b) / lambda|`` about the rigid-body motion,
decayed over the half period to its first crest (``exp(-sigma pi / omega_d)``). The swings ride on the rigid-body
force: where the rigid start's F_t (:func:`gearcli.simulate.rigid_start.integrate`, the same drive and load law
without compliance) plus the decaying swings of the modes above the samples' Nyquist frequency,
``max_t |F_rigid(t)| + sum A e^(-sigma t)``, exceeds the run's sampled peak by more than
:data:`gearcli.simulate.sampling.TARGET` of it, the stage is warned ``peak_undersampled`` (``aliased``, with
``aliased_Hz`` the mode that swings most, ``amplitude_N`` its swing and ``reach_N`` that bound), with the
``simulation.steps`` that samples the mode :data:`gearcli.simulate.sampling.GOOD_PER_PERIOD` times a period. A fast
mesh mode that a direct start rings by a few N while the force is small (the first milliseconds) reaches nowhere
near the peak and is not warned. A smooth ramp (``ramp_s > 0``) puts next to nothing into a mode many ramp-times
faster and is not a step; a stage already warned as aliased keeps its warning.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from gearcli import diagnostics as dg
from gearcli.config.schema import MAX_STEPS
from gearcli.diagnostics import Diagnostic
from gearcli.model.damping import body_matrices, lever_matrices, state_matrix
from gearcli.model.elements import machine
from gearcli.model.modes import connector_tangents
from gearcli.model.outputs import tangential_force_N
from gearcli.simulate import rigid_start
from gearcli.simulate.sampling import GOOD_PER_PERIOD, TARGET, up_to_two_figures

if TYPE_CHECKING:
    from gearcli.model import TorsionalModel


def start_torques(model: TorsionalModel) -> np.ndarray:
    """The torques (N m, per body) that act at once at t = 0: the motor's at standstill, a torque drive's and the
    load's where their ``ramp_s`` is 0 (the load at the speed the run starts its load body at)."""
    lay = model.layout
    tau = np.zeros(lay.n_bodies)
    if lay.motor_drive and lay.drive.motor is not None:
        tau[0] += float(machine.motor_torque(lay.motor_row, 0.0, 0.0)[0])
    if lay.drive.kind == "torque" and lay.drive.ramp_s == 0:
        tau[0] += float(lay.drive.torque_Nm)
    if lay.load.ramp_s == 0 and lay.load.torque_Nm != 0:
        last = lay.n_bodies - 1
        i = lay.state.omega(last)
        w = float(model.initial_state()[i]) if i is not None else 0.0
        factor = float(machine.load_factor(lay.load_law, w)[0]) if lay.load_law else 1.0
        tau[last] -= float(lay.load.torque_Nm) * factor
    return tau


def start_swings(model: TorsionalModel, first: int, duration_s: float) -> list[tuple[float, float, np.ndarray]]:
    """(damped frequency in Hz, decay rate in 1/s, |F_t| swing per stage at its first crest in N) of every mode the
    start's steps set swinging (module text); ``first``: the first free body (1 where the input's speed is
    prescribed)."""
    lay = model.layout
    tau = start_torques(model)[first:]
    if not np.any(tau) or first >= lay.n_bodies:
        return []
    k, cd = connector_tangents(lay, duration_s)
    J, K, _ = body_matrices(lay, k, cd, first)
    R, L = lever_matrices(lay, first)
    C = L.T @ (cd[:, None] * R)  # the connectors' damping alone: a motor's or load law's slope is the operating point's
    n = J.size
    lam, V = np.linalg.eig(state_matrix(J, K, C))
    try:
        a = np.linalg.solve(V, np.concatenate((np.zeros(n), tau / J)))
    except np.linalg.LinAlgError:  # a defective matrix: no modal decomposition to read
        return []
    G = np.hstack((k[:, None] * R, cd[:, None] * R))  # connector force per state (angles, speeds)
    meshes = [(s, c) for s, c in enumerate(lay.stage_conn) if lay.connectors[c].role == "mesh"]
    out = []
    for j in np.flatnonzero(lam.imag > 0.0):
        sigma, omega = -float(lam[j].real), float(lam[j].imag)
        swing = 2.0 * np.abs(G @ (V[:, j] * a[j] / lam[j])) * math.exp(-max(sigma, 0.0) * math.pi / omega)
        per_stage = np.zeros(len(lay.stage_conn))
        for s, c in meshes:
            per_stage[s] = abs(tangential_force_N(lay, s, float(swing[c])))
        out.append((omega / (2.0 * math.pi), max(sigma, 0.0), per_stage))
    return out


def peak_warnings(found: list[Diagnostic], model: TorsionalModel, boundary: str, t: np.ndarray,
                  forces_N: list[np.ndarray], steps: int) -> list[Diagnostic]:
    """``found`` (the samples' own peak warnings, :func:`gearcli.simulate.aliasing.peak_warnings`) with a
    ``peak_undersampled`` warning for every stage whose run peak a mode above the samples' Nyquist frequency, set
    swinging by the start's steps, may exceed unseen (module text), in place of a warning that bounded it;
    ``boundary``: the run's (``clamped_input`` where the input's speed is prescribed)."""
    if t.size < 2 or not float(t[-1] - t[0]) > 0.0:
        return found
    span = float(t[-1] - t[0])
    nyquist_Hz = 0.5 * (t.size - 1) / span
    first = 1 if boundary == "clamped_input" else 0
    swings = [m for m in start_swings(model, first, span) if m[0] > nyquist_Hz]
    if not swings:
        return found
    rigid = rigid_start.on_grid(model.layout, span)  # the start the run's start summary integrated (kept)
    aliased = {d.data.get("stage") for d in found if d.code == dg.PEAK_UNDERSAMPLED and d.data.get("aliased")}
    out = list(found)
    for k, ft in enumerate(forces_N):
        a = np.abs(np.asarray(ft, dtype=float))
        peak = float(a.max()) if a.size else 0.0
        if k + 1 in aliased or not peak > 0.0 or k >= rigid.tangential_N.shape[0]:
            continue
        envelope = sum(s[k] * np.exp(-sigma * rigid.time_s) for _, sigma, s in swings)
        reach = float(np.max(np.abs(rigid.tangential_N[k]) + envelope))  # the rigid force plus the swings
        if reach <= (1.0 + TARGET) * peak:
            continue
        f, _, swing = max(swings, key=lambda m: float(m[2][k]))
        i = int(np.argmax(a))
        n = up_to_two_figures(max(2.0 * steps, span * f * GOOD_PER_PERIOD))
        fix = (f"--set simulation.steps={n} samples it {GOOD_PER_PERIOD:g} times a period" if n <= MAX_STEPS else
               f"the schema's maximum simulation.steps = {MAX_STEPS} cannot sample it: sample a shorter run "
               "(simulation.duration_s)")
        out = [d for d in out if not (d.code == dg.PEAK_UNDERSAMPLED and d.data.get("stage") == k + 1)]
        out.append(dg.warning(
            dg.PEAK_UNDERSAMPLED,
            f"stage {k + 1}: the run's peak |F_t| {peak:.5g} N (at {float(t[i]):.3g} s) and its run-up factor are not "
            f"resolved by the output samples, and no estimate from them bounds the error: the step at t = 0 sets the "
            f"{f:.4g} Hz mode swinging by about ±{float(swing[k]):.3g} N in F_t about the rigid-body force, which "
            f"then reaches {reach:.5g} N, and the samples take that mode {(t.size - 1) / (f * span):.2g} times a "
            f"period (fewer than 2: its first swings, the start's peak, fall between them); {fix}",
            stage=k + 1, peak_N=peak, estimated_error_N=None, relative_error=None, steps=n if n <= MAX_STEPS else None,
            steps_cap=MAX_STEPS, aliased=True, aliased_Hz=f, amplitude_N=float(swing[k]), reach_N=reach))
    return sorted(out, key=_stage)


def _stage(d: Diagnostic) -> int:
    stage = d.data.get("stage")
    return stage if isinstance(stage, int) else 0
