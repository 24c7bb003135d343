"""A run-up vibration that an implicit run damped away after the ramps, seen in the run's own record.

Radau damps a vibration it steps over (its stability function |R(i w h)| ~ 3/(w h) for w h >> 1), and its check
pass does too, so the check pass cannot see the loss. :func:`unresolved_mode` warns
where the run takes fewer than ``MIN_STEPS_PER_PERIOD`` steps a period of a lightly damped mode over the whole
run. A run can take more than that and still lose the mode: Radau resolves a strong run-up vibration while the
ramps force small steps, and after the ramps' end its steps grow to a few periods of the mode and kill it within
a step or two. Measured (a two-stage helical reducer, 1480 rpm, 1100 N m, mesh damping ratio 1e-4, Radau at
rtol 1e-3): 99 steps over 361 periods of the 1805 Hz mode (0.27 a period, above the 0.2 limit), window F_t of
stage 1 between 2980.04 and 2980.06 N, where DOP853 at rtol 1e-10 has 2698 .. 3265 N (9.5 % of the mean off,
no warning).

What this module checks, in a scene where nothing drives the vibration after the ramps (:func:`quiet_since`):
the record itself. Over the last ``FIT_PERIODS`` periods (of the slowest such mode) before the ramps' end the
run's F_t of every stage is fitted by least squares with a quadratic trend and a cosine and a sine at each lightly
damped mode's frequency (the linearised chain at full load, which the ramps' end reaches); each mode's fitted
amplitude, decayed physically (e^(-sigma (t_w - t_q))) to the window start t_w, is what the window must still carry.
Where that sum exceeds the target (``TARGET`` of the stage's mean) and the run's window shows less than
``SHOWN`` of it (half its peak-to-peak), the run damped it numerically: the mode is returned for the
``statistics_unresolved`` warning of :func:`mode_warning`. A mode the run resolves
(the window carries it) or that the ramps hardly excite (configs/stiff_linear_mesh.toml: 0.24 steps a period of an
11.5 kHz mode of damping ratio 2.8e-4, its vibration below the target) does not warn.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from gearcli import diagnostics as dg
from gearcli.core.methods import method as method_info
from gearcli.diagnostics import Diagnostic
from gearcli.model.assembly import Layout
from gearcli.model.linear import damped_eigenvalues
from gearcli.model.outputs import Sampled, tooth_forces
from gearcli.model.planet_spec import PlanetarySpec
from gearcli.simulate.choice import Choice, excited_radians
from gearcli.simulate.estimate import AMPLITUDE, FORGOTTEN, LIGHT_DAMPING, MIN_RTOL, STATISTICS, TARGET, CheckPass
from gearcli.simulate.solver import Integration

FIT_PERIODS = 3.0  # a block of the record fitted at once, in periods of the slowest light mode
MIN_SAMPLES_PER_PERIOD = 4.0  # a mode the record samples more coarsely is not fitted
SHOWN = 0.5  # the window shows less than this share of the vibration physics keeps: it was damped numerically
MAX_BLOCKS = 200  # the record before the window is fitted in at most this many blocks (evenly spread)
MIN_STEPS_PER_PERIOD = 0.2  # an implicit run with fewer steps per period of such a mode damps it away (Radau's |R(i w h)| ~ 3/(w h): ~0.1 a step at 0.2 a period)


def quiet_since(choice: Choice, duration_s: float, sampled: Sampled | None = None) -> float | None:
    """The time from which nothing drives the chain's vibration, or None: the end of the drive's and the load's
    ramps in a scene of parallel (or quiet planetary, :func:`_quiet_stage`) stages without excitation (transmission error, stiffness harmonics, time-varying
    contact, torque ripple, load fluctuation), without backlash (impacts) and with a speed or torque drive; from
    there every mode's vibration decays at its own rate. A motor start has no end known before the run: with the
    run's record (``sampled``) it is quiet from where its start ends (:func:`motor_quiet_since`), without it never."""
    lay = choice.layout
    spec = lay.spec
    if spec.elements or not all(_quiet_stage(m) for m in spec.stage_models):
        return None
    if any(m.backlash_m > 0.0 for m in spec.meshes) or excited_radians(spec, lay, duration_s) > 0.0:
        return None
    if spec.drive.kind == "motor":
        started = None if sampled is None else motor_quiet_since(lay, sampled.time_s, sampled.omega_rad_s[0])
        return None if started is None else max(started, spec.load.ramp_s)
    return max(spec.drive.ramp_s, spec.load.ramp_s)


def motor_quiet_since(lay: Layout, t: np.ndarray, w: np.ndarray) -> float | None:
    """When a motor start's drive stops exciting the chain, from the run's motor speed ``w``: the first sample
    from which the motor stays within 2 % (:data:`gearcli.simulate.motor.START_FRACTION`) of its operating speed
    (and, starting star-delta, above its switch-over speed), not before its supply's ramp ends (a soft start's
    voltage, a VFD's speed); None where it never settles there (a stall, a motor still running up, one left in
    star). Its torque is then its curve's near the operating point, a function of speed alone: the linearised
    chain's slip damping, no forcing (a DOL mixer's 1860 Hz planet-mesh mode, excited by the start, has decayed by
    e^-550 at the window's start: Radau's window and DOP853's agree to 1e-6 of the mean force)."""
    from gearcli.simulate.motor import START_FRACTION, operating_point  # lazy: scipy.optimize, motor runs only

    motor = lay.drive.motor
    op = operating_point(lay)
    if motor is None or not op.reaches or op.speed_rad_s is None or op.speed_rad_s <= 0.0:
        return None
    off = np.abs(w - op.speed_rad_s) > (1.0 - START_FRACTION) * op.speed_rad_s
    if motor.starting == "star_delta":
        off |= w < motor.start_parameters[0]
    hit = np.nonzero(off)[0]
    if hit.size and int(hit[-1]) == t.size - 1:
        return None
    settled = float(t[int(hit[-1]) + 1]) if hit.size else float(t[0])
    ramp = motor.start_parameters[0] if motor.starting in ("soft_start", "vfd") else 0.0
    return max(settled, ramp)


def _quiet_stage(model: object) -> bool:
    """Whether a stage's own model (``ModelSpec.stage_models[k]``) drives nothing after the ramps: none (the chain's
    pair, checked with the chain), or a planetary stage whose sun and ring meshes have no excitation and no
    backlash (its planets' position errors are constant offsets); any other kind's model is not known quiet."""
    if model is None:
        return True
    if not isinstance(model, PlanetarySpec):
        return False
    return not any(m.backlash_m > 0.0 or m.time_varying or any(m.transmission_error_m) or any(m.stiffness_harmonics)
                   for m in (model.sun_mesh, model.ring_mesh))


def unresolved_mode(choice: Choice, run: Integration, duration_s: float,
                    window_start_s: float | None = None, sampled: Sampled | None = None) -> tuple[float, float] | None:
    """(frequency Hz, damping ratio) of a lightly damped mode that an implicit run steps over, or None.

    An implicit method damps vibration it does not resolve, and a second pass of it does too, so the check
    pass cannot see it. Measured: Radau on configs/extreme/stiff_linear_10000x.toml takes 51 steps over 9206
    periods of its 18 kHz undamped mesh mode and shows no vibration, where DOP853 and Radau at rtol 1e-10
    agree on a std of 15 N (0.8 % of the mean); configs/stiff_linear_mesh.toml, 0.24 steps per period of a
    mode excited far less, is resolved to 5e-5.

    A mode counts only where its vibration can reach the window (``window_start_s``): not where nothing drives it
    after the ramps (:func:`quiet_since`) and its physical decay from there to the window start is over
    ``FORGOTTEN`` e-folds (a run-up vibration of 100x the mean force left below the target). A slow crane drum
    (tests/extreme/test_quiet_mode.py): Radau's 53 steps over 1250 periods of a 12.5 Hz mode of damping ratio 0.015
    warned "not estimable", where DOP853 at rtol 1e-9 finds the window at rest to 6e-7 of the mean: the ramp's
    ringing had decayed 23 e-folds before the window.
    """
    if not method_info(run.method).implicit or duration_s <= 0:
        return None
    ev = np.concatenate([ringing_eigenvalues(choice), ringing_eigenvalues(choice, run_up=True)])
    osc = ev[np.abs(ev.imag) > 1e-9 * np.maximum(np.abs(ev), 1.0)]
    if osc.size == 0:
        return None
    zeta = -osc.real / np.abs(osc)
    light = osc[zeta < LIGHT_DAMPING]
    quiet = quiet_since(choice, duration_s, sampled)
    if quiet is not None and window_start_s is not None:  # a mode at rest in the window hides nothing
        light = light[-light.real * max(0.0, window_start_s - quiet) < FORGOTTEN]
    if light.size == 0:
        return None
    i = int(np.argmax(np.abs(light.imag)))
    f = float(abs(light[i].imag)) / (2 * math.pi)
    if run.steps >= MIN_STEPS_PER_PERIOD * f * duration_s:
        return None
    return f, float(-light[i].real / abs(light[i]))


def mode_unresolved(ref: CheckPass, mode: tuple[float, float], run: Integration,
                    duration_s: float) -> tuple[CheckPass, list[Diagnostic]]:
    """The check pass with every stage's amplitude statistics marked unresolved, and one warning per stage."""
    rtol = _tighter_rtol(run)
    errors = tuple(replace(e, unresolved=tuple(q for q in STATISTICS if q in e.unresolved or q in AMPLITUDE),
                           resolved=False, suggested_rtol=rtol) for e in ref.errors)
    return replace(ref, errors=errors), [mode_warning(k + 1, mode, run, duration_s) for k in range(len(errors))]


def _tighter_rtol(run: Integration) -> float | None:
    """The rtol that resolves a stepped-over mode (the run's / 1000, not below the schema's floor), or None at the
    floor, where no tighter rtol exists."""
    rtol = max(MIN_RTOL, run.rtol / 1000)
    return rtol if rtol < run.rtol else None


def mode_warning(stage: int, mode: tuple[float, float], run: Integration, duration_s: float) -> Diagnostic:
    f, zeta = mode
    rtol = _tighter_rtol(run)
    fix = f"--set simulation.rtol={rtol:g} or " if rtol is not None else ""
    return dg.warning(
        dg.STATISTICS_UNRESOLVED,
        f"stage {stage}: F_t min, max, std, spectrum peaks not resolved by {run.method}: its {run.steps} steps span "
        f"{f * duration_s:.3g} periods of the {f:.4g} Hz mode (damping ratio {zeta:.2g}), whose vibration it damps "
        f"numerically; the error is not estimable from this run (the check pass damps it too) — "
        f"{fix}method = \"DOP853\" resolves the mode",
        stage=stage, statistics=list(AMPLITUDE), estimated_error_N=None, relative_error=None, rtol=rtol, mode_Hz=f)


def radau_factor(omega_h: float) -> float:
    """|R(i omega h)| of the 3-stage Radau IIA method, R(z) = (1 + 2z/5 + z^2/20) / (1 - 3z/5 + 3z^2/20 - z^3/60):
    the factor by which one step of size h scales a vibration of angular frequency omega (1 for omega h -> 0,
    ~3 / (omega h) for omega h >> 1)."""
    z = 1j * omega_h
    return abs((1 + 2 * z / 5 + z * z / 20) / (1 - 3 * z / 5 + 3 * z * z / 20 - z ** 3 / 60))


def ringing_eigenvalues(choice: Choice, run_up: bool = False) -> np.ndarray:
    """The eigenvalues the chain rings at, linearised at full load (``run_up``: at the run-up load, the stiffest
    phase) with every damping and loss the run integrates (:func:`gearcli.model.linear.damped_eigenvalues`, as
    ``modes`` and the settle test take them): a lossy mesh's driven side takes eta of its force. The choice's own
    eigenvalues are the lossless chain's, which named a lossy spur stage's 329.8 Hz mode (modes: damping ratio
    9.75e-5) as 338.4 Hz, ratio 1e-4 (1 / sqrt(eta) higher, eta 0.95)."""
    lin = choice.at_operating_point if run_up else choice.at_full_load
    return np.asarray(damped_eigenvalues(choice.layout, lin.forces, stiffest_phase=run_up), dtype=complex)


def light_modes(choice: Choice, t_quiet: float, window_start_s: float, mean_step_s: float) -> list[tuple[float, float]]:
    """(omega_d rad/s, sigma 1/s) of the lightly damped modes at full load whose run-up vibration is not forgotten
    by the window start (the decay from the ramps' end to it under ``FORGOTTEN`` e-folds) and which steps of
    ``mean_step_s`` from the ramps' end to the window start shrink below ``SHOWN`` of themselves."""
    lapse_steps = max(1.0, (window_start_s - t_quiet) / mean_step_s)
    out = []
    for z in ringing_eigenvalues(choice):
        omega, sigma = float(z.imag), max(0.0, -float(z.real))
        if omega <= 0.0 or sigma / abs(z) >= LIGHT_DAMPING or sigma * max(0.0, window_start_s - t_quiet) >= FORGOTTEN:
            continue
        if radau_factor(omega * mean_step_s) ** lapse_steps < SHOWN:
            out.append((omega, sigma))
    return out


def _block(t: np.ndarray, x: np.ndarray, modes: list[tuple[float, float]], pick: np.ndarray) -> list[float]:
    """Least-squares amplitudes of ``modes`` in the samples ``pick`` (a quadratic trend besides); [] when too few."""
    t0 = float(t[pick][-1])
    tt, xx = t[pick] - t0, x[pick]
    columns = [np.ones_like(tt), tt, tt * tt] + [f(w * tt) for w, _ in modes for f in (np.cos, np.sin)]
    if tt.size < 2 * len(columns):
        return []
    coef = np.linalg.lstsq(np.column_stack(columns), xx, rcond=None)[0]
    return [math.hypot(coef[3 + 2 * j], coef[4 + 2 * j]) for j in range(len(modes))]


def carried_amplitudes(t: np.ndarray, x: np.ndarray, modes: list[tuple[float, float]],
                       window_start_s: float) -> list[float]:
    """The vibration of each of ``modes`` that ``x`` shows before the window, each block's least-squares amplitude
    decayed physically from the block's end to ``window_start_s``, the largest over the blocks; 0 for a mode the
    record samples too coarsely to tell."""
    dt = float(t[1] - t[0]) if t.size > 1 else math.inf
    fitted = [j for j, (w, _) in enumerate(modes) if 2.0 * math.pi / w >= MIN_SAMPLES_PER_PERIOD * dt]
    out = [0.0] * len(modes)
    if not fitted:
        return out
    sub = [modes[j] for j in fitted]
    span = FIT_PERIODS * 2.0 * math.pi / min(w for w, _ in sub)
    ends = np.arange(t[0] + span, window_start_s + 0.5 * dt, span)
    if ends.size > MAX_BLOCKS:
        ends = ends[np.linspace(0, ends.size - 1, MAX_BLOCKS).astype(int)]
    for end in ends:
        amps = _block(t, x, sub, (t >= end - span - 0.5 * dt) & (t <= end + 0.5 * dt))
        for a, j in zip(amps, fitted, strict=False):
            out[j] = max(out[j], a * math.exp(-modes[j][1] * max(0.0, window_start_s - end)))
    return out


def damped_ringing(choice: Choice, method: str, steps: int, sampled: Sampled, duration_s: float,
                   window: tuple[float, float]) -> tuple[float, float] | None:
    """(frequency Hz, damping ratio) of the lightly damped mode whose run-up vibration an implicit run damped away
    (module doc), or None."""
    t_quiet = quiet_since(choice, duration_s, sampled)
    if not method_info(method).implicit or t_quiet is None or window[0] < t_quiet or steps < 1:
        return None
    modes = light_modes(choice, t_quiet, window[0], duration_s / steps)
    if not modes:
        return None
    t = sampled.time_s
    in_window = (t >= window[0]) & (t <= window[1])
    if not in_window.any():
        return None
    lay = sampled.layout
    for k, mesh in enumerate(sampled.meshes):
        ft = tooth_forces(lay, k, mesh.line_force_N)[0]
        shown = 0.5 * float(np.ptp(ft[in_window]))
        carried = carried_amplitudes(t, ft, modes, window[0])
        if sum(carried) > TARGET * abs(float(np.mean(ft[in_window]))) and shown < SHOWN * sum(carried):
            omega, sigma = modes[int(np.argmax(carried))]
            return omega / (2.0 * math.pi), sigma / math.hypot(omega, sigma)
    return None
