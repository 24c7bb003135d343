"""Rigid-body loads and the linearised model: natural frequencies and the stiffness of the ODE.

Rigid body (no compliance): body speeds are ``rho_i w_0`` with ``rho_i`` the product of the radius
ratios ``r_a / r_b`` of the connectors up to body i. Connector c carries everything after it:

    F_c r_b,c = sum_{i > c} J_i alpha_i rho_i / rho_{c+1} + T_L rho_N / rho_{c+1},   alpha_i = rho_i alpha_0,

with ``alpha_0`` the STEP profile's acceleration (speed drive) or ``(T_in - rho_N T_L) / J_eff``,
``J_eff = sum J_i rho_i^2`` (torque drive).

Linearised about connector forces F_c (deflection coordinates, :mod:`gearcli.model.assembly`): each
element's force law is evaluated at the deflection that carries F_c (a mesh frozen at its mean — or
stiffest — stiffness), giving the tangent stiffness ``k_c = dF/d delta`` and damping ``c_c = dF/d delta'``.
With ``R`` the map from free body speeds to deflection rates (``delta' = R w``) the deflections obey

    delta'' = -M (K_d delta + C_d delta'),   M = R J^-1 R^T,

so the oscillating modes live in the deflection space (a free chain's rigid-body mode has no
deflection). The first-order matrix ``[[0, I], [-M K_d, -M C_d]]`` gives the eigenvalues used for the
method choice; the undamped natural frequencies are ``sqrt(eig(K^1/2 M K^1/2)) / 2 pi``.
"""

from __future__ import annotations

import math
from functools import cached_property

import numpy as np

from gearcli.core.memo import remember
from gearcli.core.records import record
from gearcli.model.assembly import Layout, power_path_loss_factors
from gearcli.model.damping import body_matrices, lever_matrices, state_matrix
from gearcli.model.spec import ModelSpec
from gearcli.model.step import ramp, ramp_rates


def _lay(x) -> Layout:
    return x if isinstance(x, Layout) else Layout.of(x)


def static_forces(lay: Layout) -> np.ndarray:
    """Force of every connector at full load in steady state: N for meshes, N m for springs.

    The statics of the power path (the parallel-stage chain): connector c carries the load torque to its
    second body, ``T_L rho_N / rho_b / r_b``. A further element (``ModelSpec.elements``) is taken to carry
    no static load (a damper; general statics come with the general topology). A lossy mesh's force is its
    driving side's: the loads of the meshes after it divided by their efficiencies (times, for a reversed
    load, whose power flows from the output). Worked out once per layout (a run asks for them in its choice, its
    tolerances, its energy scale and its statistics); a copy each time."""
    kept = lay.__dict__.get("_static_forces")
    if kept is None:
        kept = _static_forces(lay)
        lay.__dict__["_static_forces"] = kept
    return kept.copy()


def operating_forces(lay: Layout) -> np.ndarray:
    """:func:`static_forces` at the settled operating point: planets with position errors at the shares those give
    (:mod:`gearcli.model.planet_statics`; equal shares otherwise), where the model is linearised (modes, the run's
    natural frequencies). A copy each time."""
    kept = lay.__dict__.get("_operating_forces")
    if kept is None:
        kept = static_forces(lay)
        if any(x.initial_deflection for x in lay.connectors):
            from gearcli.model.planet_statics import operating_forces as settled  # lazy: planets with errors only

            kept = settled(lay, kept)
        lay.__dict__["_operating_forces"] = kept
    return kept.copy()


def _static_forces(lay: Layout) -> np.ndarray:
    rho = np.array([b.ratio for b in lay.bodies])
    rho_b = np.array([rho[x.b] for x in lay.connectors])
    rb = np.array([x.rb for x in lay.connectors])
    out = lay.load.torque_Nm * rho[-1] / rho_b / rb
    out[[c for c, x in enumerate(lay.connectors) if not x.role]] = 0.0
    for c, x in enumerate(lay.connectors):
        if x.load_body >= 0:  # a planet mesh: its share of the planetary's output torque
            out[c] = lay.load.torque_Nm * rho[-1] / rho[x.load_body] * x.load_lever
    return out * np.asarray(power_path_loss_factors(lay.spec, list(lay.connectors)))


def static_line_forces_N(spec: ModelSpec | Layout) -> np.ndarray:
    """F_bt of every mesh at full load in steady state (a lossy mesh: its driving side's), N (signed), in stage order."""
    lay = _lay(spec)
    return static_forces(lay)[list(lay.stage_conn)]


def operating_line_forces_N(lay: Layout, load_factor: float) -> np.ndarray:
    """:func:`static_line_forces_N` under ``load_factor`` x the nominal load torque (a load law's g(w) at the
    operating point), with the losses in that load's power flow: a law whose sign at the operating point is not the
    nominal one's (a torque_speed table through 0) turns the flow, so each mesh's force is then the other side's."""
    forces = static_line_forces_N(lay) * load_factor
    if load_factor >= 0.0 or not any(x.lossy for x in lay.connectors):
        return forces
    conns, meshes = list(lay.connectors), list(lay.stage_conn)
    nominal = np.asarray(power_path_loss_factors(lay.spec, conns))[meshes]
    turned = np.asarray(power_path_loss_factors(lay.spec, conns, forward=lay.load.torque_Nm < 0.0))[meshes]
    for i, c in enumerate(meshes):  # a planet mesh's own loss is in its lever: its stage's factor of the other flow
        x = conns[c]
        model = lay.spec.stage_models[x.index] if x.load_body >= 0 else None
        nominal_factor = getattr(model, f"{x.gear}_force_factor", 0.0)
        if nominal_factor:  # a planetary's (a plug-in stage model without these keeps its nominal flow's)
            turned[i] *= getattr(model, f"other_{x.gear}_force_factor", nominal_factor) / nominal_factor
    return forces * turned / nominal


def rigid_forces(lay: Layout, t: np.ndarray) -> np.ndarray:
    """Force of every connector of the rigid chain at times t, shape (connectors, len(t))."""
    t = np.asarray(t, dtype=float)
    rho = np.array([b.ratio for b in lay.bodies])
    J = np.asarray(lay.inertias)
    t_load = np.asarray(ramp(t, lay.load.ramp_s, lay.load.torque_Nm)) * np.ones_like(t)
    if lay.speed_drive:
        alpha0 = ramp_rates(t, lay.drive.ramp_s, lay.drive.speed_rad_s)[1] * np.ones_like(t)
    elif lay.motor_drive and lay.drive.motor is not None:  # run-up at the motor's largest torque
        alpha0 = (lay.drive.motor.peak_torque_Nm - rho[-1] * t_load) / float(J @ rho**2)
    else:
        t_in = np.asarray(ramp(t, lay.drive.ramp_s, lay.drive.torque_Nm)) * np.ones_like(t)
        alpha0 = (t_in - rho[-1] * t_load) / float(J @ rho**2)
    out = np.zeros((lay.n_conn, t.size))
    for c, x in enumerate(lay.connectors):
        if x.load_body >= 0:  # a planet mesh: the load's share only (the run-up inertia of a planetary is not split)
            out[c] = t_load * rho[-1] / rho[x.load_body] * x.load_lever
        elif x.role:  # on the power path: everything beyond its second body (as static_forces)
            downstream = float(J[x.b:] @ rho[x.b:] ** 2) / rho[x.b]
            out[c] = (downstream * alpha0 + t_load * rho[-1] / rho[x.b]) / x.rb
    return out


def rigid_line_forces_N(spec: ModelSpec | Layout, t: np.ndarray) -> np.ndarray:
    """F_bt,k(t) of the meshes of the rigid chain, shape (meshes, len(t)), N."""
    lay = _lay(spec)
    return rigid_forces(lay, t)[list(lay.stage_conn)]


def peak_rigid_forces(lay: Layout, duration_s: float, samples: int = 801) -> np.ndarray:
    """Largest |F_c| of the rigid chain over [0, duration] (run-up inertia plus load), per connector (read-only:
    kept per layout and span, the same for every run past the ramps: a sweep point's settle runs)."""
    end = min(duration_s, max(lay.drive.ramp_s, lay.load.ramp_s, 0.0)) or duration_s
    cache = lay.__dict__.setdefault("_peak_rigid_forces", {})
    key = (float(end), int(samples))
    if key not in cache:
        # without a ramp (a continued sweep point's model) every force is one constant from t = 0: the peak of the
        # samples is the first sample's, each sample's value worked out by the same element-wise operations
        ramped = lay.drive.ramp_s > 0.0 or lay.load.ramp_s > 0.0
        peak = np.max(np.abs(rigid_forces(lay, np.linspace(0.0, end, samples) if ramped else np.zeros(1))), axis=1)
        peak.flags.writeable = False
        cache[key] = peak
    return cache[key]


@record
class Linearisation:
    """The model linearised at one operating point: forces, tangent stiffness and damping, eigenvalues."""

    forces: np.ndarray  # the operating point, per connector (N along a mesh, N m for a spring)
    deflection: np.ndarray  # per connector: a mesh's penetration p0 (m), a spring's twist (rad)
    stiffness: np.ndarray  # k_c = dF/d delta
    damping: np.ndarray  # c_c = dF/d delta'
    eigenvalues: np.ndarray  # of the first-order deflection system (2 nc)
    natural_frequencies_Hz: np.ndarray  # undamped, ascending
    stage_conn: tuple[int, ...] = ()

    @property
    def line_forces_N(self) -> np.ndarray:
        """Per mesh, in stage order."""
        return self.forces[list(self.stage_conn)]

    @property
    def penetration_m(self) -> np.ndarray:
        return self.deflection[list(self.stage_conn)]

    @property
    def stiffness_N_m(self) -> np.ndarray:
        return self.stiffness[list(self.stage_conn)]

    # the two below: found once per linearisation, which is shared by the points that linearise the same chain
    # (:func:`linearise`, its eigenvalues read-only: :func:`_read_only`), keyed by the object itself
    @cached_property
    def max_abs_eigenvalue(self) -> float:
        return float(np.max(np.abs(self.eigenvalues))) if self.eigenvalues.size else 0.0

    @cached_property
    def min_abs_eigenvalue(self) -> float:
        nz = np.abs(self.eigenvalues)[np.abs(self.eigenvalues) > 0]
        return float(nz.min()) if nz.size else 0.0


def tangent(lay: Layout, c: int, F: float, *, stiffest_phase: bool = False) -> tuple[float, float, float]:
    """(stiffness, damping, static deflection or penetration) of connector c carrying |F|, from the
    element's own force law. A mesh is taken on its drive flank, without its gap, at its mean stiffness
    (``stiffest_phase``: its largest contact-line factor); unloaded, a linear mesh keeps K, a Hertzian
    one has no stiffness. A mesh whose law was calibrated at a floor load (an iso6336 law below 1 N/mm of face width:
    :attr:`Connector.min_line_force`) is taken at that load, where its tangent is ISO's k_n, as its reported
    ``mesh_stiffness`` is."""
    x = lay.connectors[c]
    return x.element.tangent(x.params, max(abs(float(F)), x.min_line_force), stiffest_phase)


def speed_map(lay: Layout, free: range | None = None) -> np.ndarray:
    """R with delta' = R w over the given bodies (default: the free ones)."""
    free = lay.free_bodies if free is None else free
    R = np.zeros((lay.n_conn, lay.n_bodies))
    for c, x in enumerate(lay.connectors):
        for b, lever in zip(x.bodies, x.levers, strict=True):
            R[c, b] = lever
    return R[:, free.start:free.stop]


def linearise(spec: ModelSpec | Layout, forces, *, stiffest_phase: bool = False) -> Linearisation:
    """Linearise about the given connector forces (one per connector, or per mesh when the scene has
    only meshes); ``stiffest_phase``: time-varying K at its largest factor. Kept for the last few exact inputs
    (the elements' laws and parameters, bodies, levers, inertias and forces): the points of a sweep over the speed
    linearise the same chain at the same full load, the same numbers."""
    lay = _lay(spec)
    F = np.abs(np.asarray(forces, dtype=float))
    key = (stiffest_phase, F.shape, F.tobytes(), lay.n_bodies, lay.state.first_free, tuple(lay.inertias),
           lay.stage_conn, tuple((x.kind, x.params, x.bodies, x.levers, x.min_line_force) for x in lay.connectors))
    found = _LINEARISED.get(key)
    return found if found is not None else remember(_LINEARISED, key, _read_only(_linearise(lay, F, stiffest_phase)))


def _read_only(lin: Linearisation) -> Linearisation:
    """``lin`` with its arrays read-only (shared by the points that linearise the same chain)."""
    for a in (lin.forces, lin.deflection, lin.stiffness, lin.damping, lin.eigenvalues, lin.natural_frequencies_Hz):
        a.flags.writeable = False
    return lin


_LINEARISED: dict[tuple, Linearisation] = {}  # linearise by its exact inputs


ZERO_MODE = 1e-12  # omega^2 below this fraction of the largest is a zero mode (round-off), never a frequency


def _linearise(lay: Layout, F: np.ndarray, stiffest_phase: bool) -> Linearisation:
    kd, cd, defl = np.empty(F.size), np.empty(F.size), np.empty(F.size)
    for c in range(F.size):
        kd[c], cd[c], defl[c] = tangent(lay, c, F[c], stiffest_phase=stiffest_phase)
    R = speed_map(lay)
    M = R @ np.diag(1.0 / np.asarray(lay.inertias[lay.state.first_free:])) @ R.T
    n = F.size
    A = np.zeros((2 * n, 2 * n))  # [[0, I], [-M K, -M C]] (np.block's matrix, without its Python)
    A[:n, n:] = np.eye(n)
    A[n:, :n] = -M * kd[None, :]
    A[n:, n:] = -M * cd[None, :]
    if lay.n_lossy:  # a lossy mesh passes eta of its force on (damping.py): delta'' = -R J^-1 L^T k delta
        R_, L = lever_matrices(lay, lay.state.first_free)
        omega2 = np.real(np.linalg.eigvals((R_ / np.asarray(lay.inertias[lay.state.first_free:])[None, :]) @ L.T
                                           * kd[None, :]))
    else:
        sq = np.sqrt(kd)
        omega2 = np.linalg.eigvalsh(sq[:, None] * M * sq[None, :])
    # more connectors than free bodies (a planetary's meshes) leave zero eigenvalues in this connector space: their
    # round-off (~1e-19 of the largest here) is no mode, and a rigid-body mode is none either
    omega2[omega2 <= ZERO_MODE * np.max(omega2, initial=0.0)] = 0.0
    freqs = np.sqrt(np.clip(omega2, 0.0, None)) / (2.0 * math.pi)
    return Linearisation(F, defl, kd, cd, np.linalg.eigvals(A), np.sort(freqs), lay.stage_conn)


def damped_eigenvalues(spec: ModelSpec | Layout, forces, *, stiffest_phase: bool = False) -> np.ndarray:
    """Eigenvalues of the chain linearised about the given connector forces with every damping the simulation
    integrates (:mod:`gearcli.model.damping`: the elements' laws, a motor's slip damping and the load law's
    dT/dw at the operating point, the meshes' losses), over the free bodies; lambda = -zeta omega +- i omega_d.
    A free chain adds its rigid-body eigenvalues (0, or real with a speed-dependent drive or load)."""
    lay = _lay(spec)
    F = np.abs(np.asarray(forces, dtype=float))
    kc = np.array([tangent(lay, c, F[c], stiffest_phase=stiffest_phase)[:2] for c in range(F.size)])
    return np.linalg.eigvals(state_matrix(*body_matrices(lay, kc[:, 0], kc[:, 1], lay.state.first_free)))


def damped_modes(eigenvalues: np.ndarray) -> list[tuple[float, float]]:
    """(f_d, zeta) of every oscillating eigenvalue lambda = -zeta omega +- i omega_d, once per pair, by frequency:
    the frequencies at which the linearised chain rings (f_d = omega_d / 2 pi, zeta = -Re lambda / |lambda|)."""
    lam = np.asarray(eigenvalues, dtype=complex)
    return sorted((float(z.imag / (2.0 * math.pi)), float(-z.real / abs(z))) for z in lam if z.imag > 0.0)
