"""The rigid-body start: the drivetrain without compliance, run up with the same drive and load law as the
simulation (docs/physics.md, "Rigid-body start"), the reference of ``summary.start.peak_over_rigid``.

Rigid kinematics: body i turns at ``rho_i w`` (w the input body's speed). A motor drive integrates

    (J_0 + f sum_{i>0} J_i rho_i^2 / g_i) dw/dt = T_m(t, w) - f rho_N T_L(t, rho_N w),

(T_m the motor's curve with its starting method, :func:`gearcli.model.elements.machine.motor_torque`; T_L the
load torque with its ramp and speed law; f = 1 / the train's efficiency, forward power flow; g_i the losses
between body i and the load, so that f / g_i = 1 / the efficiency of the meshes between the input and body i:
each body's inertia torque passes through the meshes before it only, as in the simulation's lossy meshes),
a torque drive the same with its input torque ramp from its nominal speed (where the simulation starts it), a
speed drive takes its prescribed ramp. The mesh force follows from the torque transmitted through the stage:
everything downstream of the mesh's driven body, its inertia reaction plus the load,

    F_c = f_c (sum_{i >= b} J_i rho_i^2 / g_i / rho_b dw/dt + rho_N / rho_b T_L) / r_b,

(f_c the losses of the meshes from c on, as the statics, so f_c / g_i those of the meshes from c to body i; a
planet mesh: the rigid bodies' equations solved for the connector forces, the planets' spin inertia included,
:func:`_planet_coefficients`).
The estimate's peak is the largest |F_t| of each stage over the run; ``peak_over_rigid`` is the simulated peak over
it. The cause of a large ratio is named from the run: a step of the drive or the load at t = 0, the motor's torque
at breakdown, a resonance passage (an excited mesh's order crossing the swinging mode during the run-up) and the
swing of the drivetrain's mode that the start excites (the deviation from the rigid force projected on each mode).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import replace

import numpy as np

from gearcli import diagnostics as dg
from gearcli.core.memo import remember
from gearcli.core.records import record
from gearcli.diagnostics import Diagnostic
from gearcli.model.assembly import Layout, power_path_loss_factors
from gearcli.model.elements import machine, mesh
from gearcli.model.modes import modal_analysis
from gearcli.model.outputs import tooth_forces
from gearcli.model.step import ramp, ramp_rates
from gearcli.simulate import rigid_flow
from gearcli.simulate.results import StartSummary
from gearcli.simulate.stats import window_slice

SAMPLES = 2001
SWING_FRACTION = 0.02  # a mode swinging with less than this of the rigid peak is not named
SWING_PERIODS = 2.0  # a mode's swing is measured over this many of its periods about the peak
STEADY_PEAK = 1.05  # a run peak within this of the window's own is the response in operation, not the start's
NOTHING_FOUND = "no step, motor torque or swinging mode explains it"
IN_OPERATION = ("which the window's statistics and dynamic factor carry (see the resonance, contact and window "
                "warnings for its cause; a gentler start does not lower it)")


@record
class RigidStart:
    """The rigid drivetrain's start: input speed and acceleration, load, line and tangential forces."""

    time_s: np.ndarray
    speed_rad_s: np.ndarray  # the input body's speed
    accel_rad_s2: np.ndarray
    load_Nm: np.ndarray  # the load torque at the load body
    line_forces_N: np.ndarray  # (connectors, samples)
    tangential_N: np.ndarray  # (stages, samples): F_t of each stage's (first) mesh
    peak_tangential_N: tuple[float, ...] = ()  # per stage, max |F_t| of the continuous start (:func:`_peaks`)


def _load_torque(lay: Layout, t: float | np.ndarray, w_load: float | np.ndarray) -> np.ndarray:
    """The load torque at time t and load speed w_load (its ramp times its speed law)."""
    base = np.asarray(ramp(np.asarray(t, float), lay.load.ramp_s, lay.load.torque_Nm), float)
    if not lay.load_law:
        return base * np.ones_like(np.asarray(w_load, float))
    g = np.vectorize(lambda w: machine.load_factor(lay.load_law, float(w))[0])(w_load)
    return base * g


def loss_factors(lay: Layout) -> np.ndarray:
    """Per connector, what the losses between it and the load multiply its force by, as the statics
    (:func:`gearcli.model.assembly.power_path_loss_factors`: a planetary's planet meshes share its power in
    parallel and count once, with the stage's efficiency, upstream of it). The rigid start's own product of every
    lossy connector's 1/eta compounded a 3-planet stage's meshes six times (1.0897 for 1.036 on
    configs/mixer_planetary_motor.toml: its rigid steady force 7 % over the design's static force)."""
    return np.asarray(power_path_loss_factors(lay.spec, list(lay.connectors)), float)


def _coefficients(lay: Layout) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """What :func:`_tangential` needs of the layout, once per start: the bodies' ratios and inertias, the connectors'
    loss factors and the planet meshes' force per unit acceleration and per unit load (the peak search calls it
    some 20 times a stage: a pseudo-inverse each time cost ~1 ms a sweep point)."""
    f = loss_factors(lay)
    return (np.array([b.ratio for b in lay.bodies]), np.asarray(lay.inertias, float) / downstream_losses(lay, f), f,
            *_planet_coefficients(lay))


def downstream_losses(lay: Layout, f: np.ndarray | None = None) -> np.ndarray:
    """Per body, g_i: what the losses between it and the load multiply a force by (module text), from the
    connector that drives it: a chain connector's ``loss_factors`` without its own loss (the power reaches the
    driven body after it). A body a planet mesh drives (a planet, a carrier) takes its planet meshes' factor (the
    stage's own loss counted before it); a body driven by nothing (the input) 1. Lossless trains: 1 everywhere.
    Dividing each inertia by it counts its inertia torque with the losses of the meshes before it only: with
    the train's whole 1/eta on every body, a lossy train's start force was 0.1 - 0.4 % off the simulation's own
    rigid limit on two 0.9 - 0.97 stages (tests/reference/test_rigid_start_losses.py)."""
    f = loss_factors(lay) if f is None else f
    forward = lay.load.torque_Nm >= 0
    g = np.ones(len(lay.bodies))
    driven = np.zeros(len(lay.bodies), bool)
    for c, x in enumerate(lay.connectors):  # chain connectors first: a planetary's input member is driven by one
        if x.load_body < 0 and len(x.bodies) == 2 and not driven[x.b]:
            g[x.b] = f[c] * (x.efficiency if forward else 1.0)
            driven[x.b] = True
    for c, x in enumerate(lay.connectors):
        if x.load_body >= 0:
            for b in x.bodies[1:]:
                if not driven[b]:
                    g[b] = f[c]
                    driven[b] = True
    g[0] = 1.0
    return g


def _tangential(lay: Layout, t: np.ndarray, w: np.ndarray, a: np.ndarray,
                coefficients: tuple) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The load torque, the line force of every connector and F_t of every stage at the rigid state (t, w, dw/dt)
    (module text); ``coefficients``: :func:`_coefficients` of ``lay``."""
    rho, J, f, per_accel, per_load = coefficients
    load = _load_torque(lay, t, w * rho[-1])
    forces = np.zeros((lay.n_conn, t.size))
    for c, x in enumerate(lay.connectors):
        if not x.role:
            continue
        if x.load_body >= 0:  # a planet mesh: the rigid bodies' equations (its planet's spin inertia included)
            forces[c] = f[c] * (per_accel[c] * a + per_load[c] * load)
            continue
        b = x.b
        downstream = float(J[b:] @ rho[b:] ** 2) / rho[b]
        torque = downstream * a + load * rho[-1] / rho[b]
        forces[c] = f[c] * torque / x.rb
    if (walks := rigid_flow.plan(lay, coefficients)) is not None:  # a mesh's power flow against the load's
        load_b = np.broadcast_to(load, t.shape)
        for i in np.flatnonzero(rigid_flow.needs_walk_mask(walks, w, a, load_b)):
            forces[:, i] = rigid_flow.walk(walks, float(w[i]), float(a[i]), float(load_b[i]))[1]
    ft = np.array([tooth_forces(lay, k, forces[c])[0] for k, c in enumerate(lay.stage_conn)])
    return load, forces, ft


def _planet_coefficients(lay: Layout) -> tuple[np.ndarray, np.ndarray]:
    """Every planet mesh's force in the rigid drivetrain per unit of its acceleration dw/dt and per unit of load
    torque: each body but the input's (whose drive torque is whatever the start gives it) obeys
    J_i rho_i dw/dt = -sum_c lever_ci F_c (minus T_L on the load body), solved with minimal norm (the planets of a
    stage share the load equally, as the rigid estimate assumes), then scaled to the planet mesh's statics (its
    share of the output torque, ``load_lever``: its sign and its own stage's losses). The stage's output torque
    alone, as before, missed the planets' own spin inertia (1.4 % of a DOL start's peak on a 3-planet stage)."""
    rho = np.array([b.ratio for b in lay.bodies])
    J = np.asarray(lay.inertias, float)
    n = len(lay.bodies)
    if not any(x.load_body >= 0 for x in lay.connectors) or n < 2:
        return np.zeros(lay.n_conn), np.zeros(lay.n_conn)
    A = np.zeros((n - 1, lay.n_conn))
    for c, x in enumerate(lay.connectors):
        for j, lever in zip(x.bodies, x.levers, strict=True):
            if j > 0:
                A[j - 1, c] += lever
    load_row = np.zeros(n - 1)
    load_row[-1] = -1.0
    pinv = np.linalg.pinv(A)
    per_accel, per_load = pinv @ (-(J * rho)[1:]), pinv @ load_row
    for c, x in enumerate(lay.connectors):
        if x.load_body < 0 or per_load[c] == 0.0:
            continue
        own = rho[-1] / rho[x.load_body] * x.load_lever / per_load[c]
        per_accel[c], per_load[c] = own * per_accel[c], own * per_load[c]
    return per_accel, per_load


def _stage_force(lay: Layout, k: int, coefficients: tuple) -> Callable[[float, float, float], float]:
    """Stage k's F_t at one rigid state ``(t, w, dw/dt)`` as a function on floats: the operations of
    :func:`_tangential` (and :func:`_load_torque`, :func:`gearcli.model.step.ramp`, :func:`tooth_forces`) for
    this stage alone, in the same order, so the same number bit for bit (tests/simulate/test_rigid_start_peaks.py).
    The peak search evaluates it some 20 times a stage: the arrays of every connector cost ~0.1 ms a call."""
    rho, J, f, per_accel, per_load = coefficients
    c = lay.stage_conn[k]
    x = lay.connectors[c]
    cos_a = math.cos(lay.spec.meshes[k].transverse_pressure_angle_rad)
    rho_n, ramp_s, torque_Nm, law = float(rho[-1]), float(lay.load.ramp_s), float(lay.load.torque_Nm), lay.load_law

    def load_at(t: float, w_load: float) -> float:
        if ramp_s <= 0.0:
            base = torque_Nm
        else:  # gearcli.model.step.step(t, 0, 0, ramp_s, torque_Nm)
            s = min(max((t - 0.0) / (ramp_s - 0.0), 0.0), 1.0)
            base = 0.0 + (torque_Nm - 0.0) * s * s * (3.0 - 2.0 * s)
        return base if not law else base * machine.load_factor(law, w_load)[0]

    if not x.role:
        return lambda t, w, a: 0.0
    if x.load_body >= 0:
        fc, pa, pl = float(f[c]), float(per_accel[c]), float(per_load[c])
        return lambda t, w, a: fc * (pa * a + pl * load_at(t, w * rho_n)) * cos_a
    b = x.b
    downstream = float(float(J[b:] @ rho[b:] ** 2) / rho[b])
    rho_b, fc, rb = float(rho[b]), float(f[c]), float(x.rb)
    if (walks := rigid_flow.plan(lay, coefficients)) is not None:
        def walked(t: float, w: float, a: float) -> float:
            load = load_at(t, w * rho_n)
            if rigid_flow.needs_walk(walks, w, a, load):
                return rigid_flow.walk(walks, w, a, load)[1][c] * cos_a
            return fc * (downstream * a + load * rho_n / rho_b) / rb * cos_a
        return walked
    return lambda t, w, a: fc * (downstream * a + load_at(t, w * rho_n) * rho_n / rho_b) / rb * cos_a


def _peaks(lay: Layout, state, times: np.ndarray, ft: np.ndarray, coefficients: tuple) -> tuple[float, ...]:
    """Per stage, the largest |F_t| of the continuous rigid start: the largest over ``times`` (the output grid and
    the integrator's own steps, which follow every fast change of the drive: a star-delta switch-over, the end of a
    ramp), refined by a bounded scalar search between the neighbouring times on the continuous state ``state(t) ->
    (w, dw/dt)`` (floats). The output grid alone misses a short peak (a star-delta switch-over against a fan load:
    1.8 % below the peak on 2001 samples over 3 s)."""
    from scipy.optimize import fminbound  # lazy: scipy, start-up time

    out = []
    for k in range(ft.shape[0]):
        force = _stage_force(lay, k, coefficients)

        def negative_magnitude(tt: float, force=force) -> float:  # what the search minimises
            w, a = state(tt)
            return -abs(force(tt, w, a))

        i = int(np.argmax(np.abs(ft[k])))
        best = float(abs(ft[k][i]))
        lo, hi = float(times[max(i - 1, 0)]), float(times[min(i + 1, times.size - 1)])
        if hi > lo:  # scipy's bounded Brent (minimize_scalar(method="bounded")'s own search, without its wrapping)
            fun = fminbound(negative_magnitude, lo, hi, xtol=1e-12 * max(hi, 1.0), full_output=True, disp=0)[1]
            best = max(best, -float(fun))
        out.append(best)
    return tuple(out)


def integrate(lay: Layout, duration_s: float, samples: int = SAMPLES) -> RigidStart:
    """The rigid start over [0, duration_s] (module text)."""
    return _refined(*_on_grid(lay, duration_s, samples))


def on_grid(lay: Layout, duration_s: float) -> RigidStart:
    """The rigid start over [0, duration_s] on its grid, its peaks not refined (``peak_tangential_N`` empty): the
    same integration :func:`start_summary` makes of a run, kept (:func:`_on_grid`)."""
    return _on_grid(lay, duration_s)[1]


def _refined(lay: Layout, rigid: RigidStart, state, times: np.ndarray, ft_all: np.ndarray,
             coefficients: tuple) -> RigidStart:
    """``rigid`` (:func:`_on_grid`) with its peaks refined on the continuous state (:func:`_peaks`)."""
    return replace(rigid, peak_tangential_N=_peaks(lay, state, times, ft_all, coefficients))


def _speed_motion(lay: Layout, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """A speed drive's prescribed input speed and acceleration at the times ``t`` (its ramp)."""
    ww, aa = ramp_rates(t, lay.drive.ramp_s, lay.drive.speed_rad_s)
    return np.asarray(ww, float) * np.ones_like(t), np.asarray(aa, float) * np.ones_like(t)


def _speed_state(lay: Layout) -> Callable[[float], tuple[float, float]]:
    """A speed drive's continuous state ``state(t) -> (w, dw/dt)`` on floats: :func:`_speed_motion` at one time,
    the same operations (:func:`gearcli.model.step.ramp_rates`)."""
    ramp_s, speed = float(lay.drive.ramp_s), float(lay.drive.speed_rad_s)

    def state(tt: float) -> tuple[float, float]:
        if ramp_s <= 0.0:
            return speed, 0.0
        s = min(max(tt / ramp_s, 0.0), 1.0)
        return speed * s * s * (3.0 - 2.0 * s), 6.0 * speed * s * (1.0 - s) / ramp_s

    return state


def _on_grid(lay: Layout, duration_s: float, samples: int = SAMPLES) -> tuple:
    """The rigid start on its grid, before its peaks are refined: (lay, the start without ``peak_tangential_N``,
    the continuous state ``state(t) -> (w, dw/dt)``, the times the peaks are sought about, F_t at them, the
    coefficients of :func:`_tangential`): the arguments of :func:`_refined`. Kept for the last layouts and durations
    asked (a run's start summary and its start-ring bound, :mod:`gearcli.simulate.start_rings`, integrate the same
    start; the kept tuple holds its layout, so an id is never another layout's while kept)."""
    key = (id(lay), duration_s, samples)
    found = _GRIDS.get(key)
    if found is not None and found[0] is lay:
        return found
    return remember(_GRIDS, key, _integrate_on_grid(lay, duration_s, samples), cap=2)


_GRIDS: dict[tuple[int, float, int], tuple] = {}  # _on_grid by layout (its id), duration and samples


def _integrate_on_grid(lay: Layout, duration_s: float, samples: int) -> tuple:
    """:func:`_on_grid`, computed."""
    from scipy.integrate import solve_ivp  # lazy: scipy, start-up time

    coefficients = _coefficients(lay)
    rho, J = coefficients[0], coefficients[1]  # J: each inertia over the losses between it and the load
    # the whole train's losses (a planetary's as its stage efficiency); f0 / g_i those before body i
    f0 = 1.0 / lay.train_efficiency(True) if lay.load.torque_Nm >= 0 else lay.train_efficiency(False)
    j_eff = float(J[0] + f0 * (J[1:] @ rho[1:] ** 2))
    t = np.linspace(0.0, duration_s, samples)
    if lay.speed_drive:
        w, a = _speed_motion(lay, t)
        steps = np.array([], float)
        state = _speed_state(lay)
    else:
        row = lay.motor_row if lay.motor_drive else ()

        def drive(tt: float, w: float) -> float:
            if lay.motor_drive:
                return machine.motor_torque(row, tt, w)[0]
            return float(ramp(tt, lay.drive.ramp_s, lay.drive.torque_Nm))

        walks = rigid_flow.plan(lay, coefficients)  # a mesh's power flow may turn against the load's

        def rhs(tt: float, y: np.ndarray) -> list[float]:
            load = float(_load_torque(lay, tt, y[0] * rho[-1]))
            a0 = (drive(tt, y[0]) - f0 * rho[-1] * load) / j_eff
            if walks is not None and rigid_flow.needs_walk(walks, float(y[0]), a0, load):
                return [rigid_flow.acceleration(walks, float(y[0]), drive(tt, y[0]), load, a0)]
            return [a0]

        w0 = 0.0 if lay.motor_drive else lay.drive.speed_rad_s  # as the simulation: a torque drive at its nominal speed
        sol = solve_ivp(rhs, (0.0, duration_s), [w0], method="LSODA", rtol=1e-9, atol=1e-9,
                        max_step=duration_s / 200, dense_output=True)
        w = sol.sol(t)[0] if sol.success else np.interp(t, sol.t, sol.y[0])
        a = np.array([rhs(tt, np.array([ww]))[0] for tt, ww in zip(t, w, strict=True)])
        steps = np.asarray(sol.t, float) if sol.success else np.array([], float)

        def state(tt: float) -> tuple[float, float]:
            ww = float(sol.sol(tt)[0]) if sol.success else float(np.interp(tt, sol.t, sol.y[0]))
            return ww, rhs(tt, np.array([ww]))[0]
    load, forces, ft = _tangential(lay, t, w, a, coefficients)
    # the peaks over the grid and the integrator's steps, each refined on the continuous state
    times, ft_all = t, ft  # a speed drive's: the grid (increasing: its own np.unique)
    if steps.size:
        times = np.unique(np.concatenate((t, steps[(steps >= 0.0) & (steps <= duration_s)])))
        ws_as = np.array([state(float(tt)) for tt in times])
        ft_all = _tangential(lay, times, ws_as[:, 0], ws_as[:, 1], coefficients)[2]
    return lay, RigidStart(t, w, a, load, forces, ft), state, times, ft_all, coefficients


def cause(lay: Layout, rigid: RigidStart, peak_time_s: float, swinging: tuple[float, str, float] | None) -> str:
    """What makes the start's peak (module text), in words for the ``peak_over_rigid`` warning; ``swinging`` the
    mode that swings in the start (:func:`swing`)."""
    parts = shocks(lay)
    if swinging is not None:
        f, element, amplitude = swinging
        passage = resonance_passage(lay, rigid, peak_time_s, f)
        dominated = f" (dominated by the {element})" if element else ""
        parts.append((passage + ", and " if passage else "") +
                     f"the {f:.3g} Hz mode{dominated} swings with ±{amplitude:.4g} N about the rigid-body force "
                     "during the start: more damping there or a gentler start (soft start, VFD, longer ramps) "
                     "lowers it")
    return "; ".join(parts) if parts else (f"{NOTHING_FOUND}: a violent impact or a numerical artefact — check with a "
                                           "tighter rtol")


def shocks(lay: Layout) -> list[str]:
    """What the drive and load put into the drivetrain at once at t = 0, in words: a step (``ramp_s = 0``) and its
    fix, the motor's locked-rotor and breakdown torque."""
    parts = [step] if (step := step_text(lay)) else []
    if lay.motor_drive and lay.drive.motor is not None:
        t_lr = machine.motor_torque(lay.motor_row, 0.0, 0.0)[0]
        parts.append(f"the motor applies its locked-rotor torque ({t_lr:.4g} N·m) at once when switched on and "
                     f"its breakdown torque ({lay.drive.motor.peak_torque_Nm:.4g} N·m) on the way up: a torque "
                     "step that an elastic drivetrain answers with up to twice the rigid-body force")
    return parts


def step_text(lay: Layout) -> str:
    """The drive or load applied as a step at t = 0 (``ramp_s = 0``) and its fix, in words; empty without one."""
    steps = []
    if lay.drive.kind == "speed" and lay.drive.ramp_s == 0 and lay.drive.speed_rad_s != 0:
        steps.append("[input] speed")
    if lay.drive.kind == "torque" and lay.drive.ramp_s == 0 and lay.drive.torque_Nm != 0:
        steps.append("[input] torque")
    if lay.load.ramp_s == 0 and abs(float(_load_torque(lay, 0.0, 0.0))) > 0:
        steps.append("[load]")
    if not steps:
        return ""
    return (f"the {' and '.join(steps)} step at t = 0 (ramp_s = 0) shocks the mesh: give ramp_s > 0 (several periods "
            "of the lowest natural frequency) for a smooth run-up; a tighter rtol does not change a physical shock")


def prestress_cause(lay: Layout, k: int, initial_te: list[float], force0_N: float, peak_time_s: float) -> str:
    """Stage k's start peak explained by the drivetrain's pre-stress at t = 0 (module text): every body starts at
    rest at zero angle, so a mesh whose transmission error is not 0 at phase 0 starts compressed by e(0), its own
    force at t = 0 (``force0_N``) or, released, a load on its neighbours in the first mode periods. Names the
    pre-stressed meshes and what removes the peak (a TE that is 0 at t = 0) or leaves it out (the steady window);
    no ramp, damping or rtol lowers a force the initial state holds."""
    others = " and ".join(f"the stage {j + 1} mesh's transmission error e(0) = {e:.3g} µm"
                          for j, e in enumerate(initial_te) if e != 0.0 and j != k)
    if initial_te[k] != 0.0:
        why = (f"the stage {k + 1} mesh starts compressed by its transmission error e(0) = {initial_te[k]:.3g} µm "
               f"(every body starts at rest at zero angle), {force0_N:.5g} N at t = 0 before anything turns"
               + (f", and {others} pre-stresses the drivetrain too" if others else ""))
    else:
        why = (f"the drivetrain starts pre-stressed by {others} (every body starts at rest at zero angle), and this "
               f"mesh takes the pre-stress up as the bodies move, {1e3 * peak_time_s:.3g} ms in")
    besides = "".join(f"; besides, {part}" for part in shocks(lay))
    return (why + ": no ramp, damping or tighter rtol lowers a force the initial state holds; a TE that is 0 at "
            "t = 0 removes it (transmission_error_phase_deg = 90 for one harmonic, in general phases with "
            "Σ e_j cos ψ_j = 0), and the steady window leaves it out (simulation.window_start_s: the window's "
            "statistics never include the start, the run-up factor and the start's peak do)" + besides)


#: a pre-stress explains a start peak when its own force at t = 0, over its stage's rigid-body peak, is at least
#: this share of the peak's ratio (the seed's few-µm TE under its 35 kN run-up is far below; a TE that holds a
#: lightly loaded mesh at several times its load is above)
PRESTRESS_SHARE = 0.5


def prestress_explains(peak_time_s: float, ratio: float, prestress_ratios: list[float],
                       modes: list[tuple[float, str]]) -> bool:
    """Whether a start peak of ``ratio`` (over the rigid-body peak) at ``peak_time_s`` is the initial state's: the
    largest pre-stress (|F_j(0)| over stage j's rigid-body peak, ``prestress_ratios``) reaches
    :data:`PRESTRESS_SHARE` of it, and the peak comes at t = 0 or within one period of the lowest natural frequency
    (the pre-stress is released on the modes' time scale, a ramp's force builds on the ramp's)."""
    if max(prestress_ratios, default=0.0) < PRESTRESS_SHARE * ratio:
        return False
    lowest = min((f for f, _ in modes if f > 0), default=None)
    return peak_time_s == 0.0 or (lowest is not None and peak_time_s <= 1.0 / lowest)


def resonance_passage(lay: Layout, rigid: RigidStart, peak_time_s: float, mode_Hz: float | None) -> str:
    """An excited mesh's order (1x its mesh frequency: a transmission error or a varying stiffness) crossing
    ``mode_Hz`` during the run-up before the peak, named with its time; empty when none does."""
    if mode_Hz is None or mode_Hz <= 0:
        return ""
    orders: list[tuple[str, float]] = []  # Hz per (rad/s of the input body)
    for c in lay.stage_conn:
        x = lay.connectors[c]
        if not x.element.makes_excitation(x.params):  # a mesh without excitation makes no order to pass through
            continue
        try:
            period = x.element.cycle_period_s(x.params, lay.bodies[x.a].ratio)
        except (AttributeError, ZeroDivisionError, ValueError):
            continue
        if period and math.isfinite(period):
            orders.append((f"stage {x.index + 1}'s mesh frequency", 1.0 / period))
    w = np.abs(rigid.speed_rad_s)
    for name, order in orders:
        f = order * w
        hit = np.nonzero((f[:-1] < mode_Hz) & (f[1:] >= mode_Hz))[0]
        if hit.size and rigid.time_s[hit[0]] <= peak_time_s:
            return (f"{name} passes through the {mode_Hz:.3g} Hz mode at {rigid.time_s[hit[0]]:.3g} s of the run-up "
                    "(a resonance passage)")
    return ""


def swing(t: np.ndarray, deviation: np.ndarray, modes: list[tuple[float, str]],
          min_amplitude_N: float, peak_time_s: float | None = None) -> tuple[float, str, float] | None:
    """The mode that swings at the start's peak: the deviation of the simulated force from the rigid one projected on
    each mode's frequency over ``SWING_PERIODS`` of its periods about ``peak_time_s`` (shifted into the span where the
    peak lies near its start or end; the span's middle without a peak time), the window's own mean removed (the DFT
    amplitude 2 |sum x e^(-i w t)| / n; modes with at least that many periods in the span and four samples per period);
    the largest, as (frequency, dominant element, amplitude), when it reaches ``min_amplitude_N``; else None. The
    amplitude is the swing's where the peak is: a lightly damped mode rung by a step decays long before the window
    starts, so its amplitude averaged over the whole start would be a small fraction of the swing that made the peak."""
    if t.size < 16 or t[-1] <= t[0]:
        return None
    span, dt = t[-1] - t[0], (t[-1] - t[0]) / (t.size - 1)
    centre = 0.5 * (t[0] + t[-1]) if peak_time_s is None else float(peak_time_s)
    best: tuple[float, str, float] | None = None
    for f, element in modes:
        if f * span < SWING_PERIODS or f * dt > 0.25:
            continue
        width = SWING_PERIODS / f
        lo = min(max(centre - 0.5 * width, t[0]), t[-1] - width)
        sel = (t >= lo) & (t <= lo + width)
        x = deviation[sel] - deviation[sel].mean()
        amplitude = 2.0 * abs(np.sum(x * np.exp(-2j * math.pi * f * t[sel]))) / x.size
        if best is None or amplitude > best[2]:
            best = (f, element, float(amplitude))
    return best if best is not None and best[2] >= min_amplitude_N else None


def initial_te_um(lay: Layout, k: int) -> float:
    """Stage k's static transmission error at t = 0 in µm: its mesh's e(phi) at the phase 0 every body starts from;
    0 for a stage that is no pair mesh (a planetary's) or has no transmission error."""
    x = lay.connectors[lay.stage_conn[k]]
    if x.role != "mesh" or not x.excited:
        return 0.0
    return 1e6 * mesh.transmission_error(x.params, 0.0)[0]


def start_summary(lay: Layout, boundary: str, t: np.ndarray, forces_N: list[np.ndarray], window_s: tuple[float, float],
                  warn_ratio: float, reswitch_s: float | None = None, *, summary: bool = True,
                  peaks_N: Sequence[float] | None = None) -> tuple[StartSummary | None, list[Diagnostic]]:
    """``summary.start`` = {``peak_over_rigid``, ``rigid_peak_N``} per stage (the run's peak |F_t| over the rigid
    start's) and the ``peak_over_rigid`` warnings where the ratio exceeds ``warn_ratio``, naming the cause;
    ``reswitch_s`` the time a star-delta motor first fell back into star (a peak after it is named with it).
    ``summary=False``: the warnings alone, the summary None (a caller that reads none: a sweep row, a duty point),
    and the rigid peaks refined only where a warning may follow: a refined peak is at least the grid's largest
    |F_t|, so a run peak within ``warn_ratio`` of that (the same division) is within it of the refined one too; a
    speed drive's is judged on the grid's last sample first, before the grid is made (:func:`_no_warning_at_end`).
    ``peaks_N``: each stage's run peak max |F_t| where the caller has it (``StageDynamics.peak_tangential_N``)."""
    if t.size < 2 or t[-1] <= 0:
        return None, []
    peaks = [float(np.max(np.abs(f))) for f in forces_N] if peaks_N is None else [float(p) for p in peaks_N]
    if not summary and _no_warning_at_end(lay, float(t[-1]), peaks, warn_ratio):
        return None, []
    grid = _on_grid(lay, float(t[-1]))
    if not summary and _no_warning(peaks, grid[1].tangential_N, warn_ratio):
        return None, []
    rigid = _refined(*grid)
    rigid_peaks = list(rigid.peak_tangential_N)
    ratios = [p / r if r > 0 else None for p, r in zip(peaks, rigid_peaks, strict=True)]
    out = StartSummary(peak_over_rigid=ratios, rigid_peak_N=rigid_peaks)
    diags: list[Diagnostic] = []
    start = t <= max(window_s[0], t[0])
    in_window = t >= window_s[0]
    inside = window_slice(in_window)  # read in place where contiguous (ascending times): the mask's numbers
    window_peaks = [float(np.max(np.abs(f[inside]))) if np.any(in_window) else 0.0 for f in forces_N]
    modes: list[tuple[float, str]] | None = None
    initial_te = [initial_te_um(lay, k) for k in range(len(forces_N))]
    prestress = [abs(float(f[0])) / r for f, r, e in zip(forces_N, rigid_peaks, initial_te, strict=True)
                 if e != 0.0 and r > 0]
    for k, ratio in enumerate(ratios):
        if ratio is None or ratio <= warn_ratio:
            continue
        if modes is None:
            modes = [(m.frequency_Hz, m.dominant) for m in modal_analysis(lay, boundary).modes if not m.rigid]
        i = int(np.argmax(np.abs(forces_N[k])))
        # signed: a force swinging through zero (a reversing mesh) keeps its fundamental, which |F| would fold
        dev = forces_N[k][start] - np.interp(t[start], rigid.time_s, rigid.tangential_N[k])
        if prestress_explains(float(t[i] - t[0]), ratio, prestress, modes):  # the initial state's, not the start's
            found = None
            why = prestress_cause(lay, k, initial_te, abs(float(forces_N[k][0])), float(t[i] - t[0]))
        elif t[i] > window_s[0]:  # the run's peak lies in the statistics window: the response there, not the start's
            found = None
            why = (f"the peak lies in the statistics window (from {window_s[0]:.4g} s), not in the start: it is the "
                   f"response in operation, {IN_OPERATION}")
        elif peaks[k] <= STEADY_PEAK * window_peaks[k]:  # the window reaches it too: the steady response's peak
            found = None
            named = cause(lay, rigid, float(t[i]), None)  # a step or the motor, named; no swing of the start
            why = ("" if named.startswith(NOTHING_FOUND) else named + "; ") + (
                f"the statistics window (from {window_s[0]:.4g} s) reaches {window_peaks[k]:.5g} N too, within "
                f"{100 * (STEADY_PEAK - 1):.0f} % of the peak: it is the response in operation, {IN_OPERATION}")
        else:
            found = swing(t[start], dev, modes, SWING_FRACTION * rigid_peaks[k], float(t[i]))
            why = cause(lay, rigid, float(t[i]), found)
            if why.startswith(NOTHING_FOUND) and window_peaks[k] > warn_ratio * rigid_peaks[k]:
                # the response in operation alone is over the ratio: the start runs into it, it is no artefact
                why = (f"the statistics window (from {window_s[0]:.4g} s) reaches {window_peaks[k]:.5g} N, itself "
                       f"{window_peaks[k] / rigid_peaks[k]:.3g}x the rigid start's peak: the start runs into the "
                       f"response in operation and overshoots it by {100 * (peaks[k] / window_peaks[k] - 1):.2g} %, "
                       f"{IN_OPERATION}")
        if reswitch_s is not None and t[i] >= reswitch_s and t[i] <= window_s[0]:
            why = (f"the star-delta motor fell back into star at {reswitch_s:.4g} s and toggles star and delta on its "
                   "rotor's swings (star_delta_reswitch), which the rigid start does not and a latching starter does "
                   "not either; besides: " + why)
        diags.append(dg.warning(dg.PEAK_OVER_RIGID, f"stage {k + 1}: the start's peak mesh force {peaks[k]:.5g} N "
                                f"(at {t[i]:.3g} s) is {ratio:.3g}x the rigid-body start's {rigid_peaks[k]:.5g} N (the "
                                f"same drive and load law without compliance): {why}", stage=k + 1, ratio=ratio,
                                rigid_peak_N=rigid_peaks[k], swing_Hz=found[0] if found else None,
                                swing_amplitude_N=found[2] if found else None))
    return (out if summary else None), diags


def _no_warning_at_end(lay: Layout, duration_s: float, peaks: list[float], warn_ratio: float,
                       samples: int = SAMPLES) -> bool:
    """:func:`_no_warning` judged on a few samples of a speed drive's rigid start grid (:func:`_on_grid`'s), before
    the grid is made: the two about the drive ramp's middle (its largest acceleration) and the last. Each sample's
    |F_t| (:func:`_stage_force` at :func:`_grid_time`, the grid's own number bit for bit) is at most the grid's
    largest, so a ratio within ``warn_ratio`` of the largest of them is within it of the grid's largest too; False
    (the grid decides) for another drive, whose rigid start is integrated."""
    if not lay.speed_drive or samples < 2:
        return False
    middle = int(0.5 * float(lay.drive.ramp_s) / duration_s * (samples - 1))
    times = [_grid_time(i, duration_s, samples) for i in sorted({middle, middle + 1, samples - 1}) if 0 <= i < samples]
    coefficients, state = _coefficients(lay), _speed_state(lay)
    motion = [state(tt) for tt in times]
    ends = []
    for k in range(len(lay.stage_conn)):
        force = _stage_force(lay, k, coefficients)
        ends.append(max(abs(force(tt, w, a)) for tt, (w, a) in zip(times, motion, strict=True)))
    return all(g > 0 and p / g <= warn_ratio for p, g in zip(peaks, ends, strict=True))


def _grid_time(i: int, duration_s: float, samples: int) -> float:
    """Sample ``i`` of ``numpy.linspace(0.0, duration_s, samples)`` (``samples`` >= 2), the same number: numpy's
    ``i * step + 0.0`` with ``step = duration_s / (samples - 1)``, the last sample ``duration_s`` itself."""
    return duration_s if i == samples - 1 else i * (duration_s / (samples - 1)) + 0.0


def _no_warning(peaks: list[float], rigid_ft: np.ndarray, warn_ratio: float) -> bool:
    """No stage's ratio can exceed ``warn_ratio``: each run peak over the largest |F_t| of the rigid start's grid
    ``rigid_ft`` (stages x samples; positive) is within it; the refined peak, not below that largest, only lowers
    the ratio (a correctly rounded division is monotone in its divisor)."""
    grid = [float(np.max(np.abs(f))) for f in rigid_ft]
    return all(g > 0 and p / g <= warn_ratio for p, g in zip(peaks, grid, strict=True))
