"""``method = "auto"``: explicit or implicit, and which engine, from a cost model of both on the linearised scene.

The model is linearised (:func:`gearcli.model.linearise`) twice: at full static load (the reported
natural frequencies) and at the larger of the static and the rigid-body run-up force of each mesh,
with a time-varying stiffness at its stiffest phase (a Hertz mesh stiffens with its load, so the run-up
sets the largest eigenvalue). The stiffness indicator is ``max|lambda| T`` over both, T the run length.

What each method needs (the constants and their measurements: :mod:`gearcli.core.cost`):

- the vibration to resolve, P radians: the largest omega_j min(T, 5/sigma_j) over the modes of the
  linearised chain that something excites, omega_j the mode's frequency and sigma_j its decay rate (from the
  modal damping of the connectors). A mode is excited when a self-exciting mesh (Hertzian exponent,
  time-varying stiffness or backlash) holds at least 1 % of its strain energy, or when the drive and load
  ramps leave a residual vibration of at least rtol: 6/(omega T_r)^2 for a STEP ramp of T_r (1 for a ramp
  of 0). A very stiff linear mesh ramped smoothly (configs/stiff_linear_mesh.toml) stays unexcited: Radau
  steps over it, DOP853 must stay stable on it;
- the excitation to follow, E radians: the largest phase the highest harmonic of any excitation sweeps over
  the run (a mesh's transmission error, stiffness harmonics or contact-line stiffness: harmonic x pinion teeth
  x pinion angle; torque ripple: order x input angle; load fluctuation: 2 pi f T), the angles from the drive's
  STEP profile. The forced response must be resolved over the whole run by either method;
- DOP853: max(2.6 max|lambda| T, 6 P + 35 E) evaluations; Radau: 1000 + 17 P + 30 E.

Each is priced on the engine that would run it (the compiled engine's ~0.4 µs per evaluation, or scipy's
~10 µs, plus what loading the compiled engine still costs this process), and ``auto`` takes DOP853 unless
Radau's predicted wall time is ``IMPLICIT_MARGIN`` times lower, both with the loading aside: each method is priced
on the engine that would run it were the kernel loaded, so that the choice does not depend on the load. It takes
Radau, and a course change never moves to DOP853, where a lossy mesh's power-flow sign flips with the run-up's
vibration (:func:`sign_flips`: a crawl speed; docs/numerics.md "Losses at crawl speeds").
"""

from __future__ import annotations

import math
from functools import cached_property

import numpy as np

from gearcli.core.cost import (
    EXPLICIT_CAP,
    IMPLICIT_MARGIN,
    STIFFNESS_LIMIT,
    ModelSize,
    predicted_evaluations,
    predicted_wall_s,
)
from gearcli.core.memo import remember
from gearcli.core.methods import AUTO, EXPLICIT, EXPLICIT_METHOD, IMPLICIT_METHOD, method
from gearcli.core.records import record
from gearcli.model import Layout, Linearisation, ModelSpec, linearise
from gearcli.model.assembly import loss_speeds
from gearcli.model.contact_lines import shortest_stretch
from gearcli.model.elements import mesh
from gearcli.model.linear import damped_eigenvalues, operating_forces, peak_rigid_forces, speed_map, static_forces

DECAY_TIMES = 5.0  # a mode's vibration lasts 5 / sigma after it is excited
SELF_EXCITING_SHARE = 0.01  # strain-energy share of a nonlinear/time-varying/backlash mesh that excites a mode
__all__ = ["EXPLICIT", "EXPLICIT_METHOD", "IMPLICIT_METHOD", "STIFFNESS_LIMIT", "Choice", "choose_method"]


@record
class Choice:
    """The integration method chosen for a run, why, and the linearisations and cost model behind it."""

    method: str
    requested: str
    reason: str
    indicator: float  # max|lambda| T
    stiffness_ratio: float  # max|lambda| / min|lambda|
    at_full_load: Linearisation
    at_operating_point: Linearisation
    spec: ModelSpec
    layout: Layout
    vibration_rad: float = 0.0  # P: radians of excited, persisting vibration (cost model)
    predicted_evals: tuple[float, float] = (0.0, 0.0)  # (DOP853, Radau) predicted evaluations
    excited_rad: float = 0.0  # E: radians of the highest excitation harmonic over the run (cost model)
    predicted_s: tuple[float, float] = (0.0, 0.0)  # (DOP853, Radau) predicted wall time on their engines
    engines: tuple[str, str] = ("python", "python")  # the engine each prediction is priced on
    size: ModelSize = ModelSize()  # what the price per evaluation depends on (gearcli.core.cost.PRICE_US)
    explicit_barred: str = ""  # why auto offers no explicit method, neither at the start nor on a course change
    auto_method: str = EXPLICIT_METHOD  # what ``auto`` takes on this scene at these prices (a requested method too)

    @property
    def reported(self) -> Linearisation:
        """The linearisation a run's modes refer to: at full load, or at the run-up load when a connector has no
        stiffness at full load (an unloaded Hertzian mesh)."""
        return self.at_operating_point if bool(np.any(self.at_full_load.stiffness == 0.0)) else self.at_full_load

    @property
    def natural_frequencies_Hz(self) -> tuple[float, ...]:
        """Undamped natural frequencies to report (:attr:`reported`), zero modes left out."""
        return tuple(float(f) for f in self.reported.natural_frequencies_Hz if f > 0)

    @cached_property
    def run_eigenvalues(self) -> np.ndarray:
        """The eigenvalues of :attr:`reported` with every damping the run integrates (a motor's slip damping, the
        load law's dT/dw: :func:`gearcli.model.linear.damped_eigenvalues`), as ``modes`` takes them: the window's
        settle test and its ringing fit read the same ones, worked out once per run."""
        return damped_eigenvalues(self.layout, self.reported.forces)

    @property
    def boundary(self) -> str:
        """The boundary condition of the reported frequencies: a speed drive holds the input body."""
        return "clamped_input" if self.layout.speed_drive else "free"

    @cached_property
    def stiffest_connector(self) -> int:
        """The connector that makes the scene stiff: the largest strain-energy share of the fastest mode, over the
        linearisation with the larger max|lambda| (a coupling or a flexible shaft as well as a mesh)."""
        lin = max((self.at_full_load, self.at_operating_point), key=lambda x: x.max_abs_eigenvalue)
        return fastest_mode_connector(lin, self.layout)

    @property
    def stiff_element(self) -> tuple[str, str]:
        """(the element that makes the scene stiff, in a message's words; what to check of it)."""
        return element_name(self.layout, self.stiffest_connector), stiffness_keys(self.layout, self.stiffest_connector)

    def explicit_evaluations(self, name: str = EXPLICIT_METHOD) -> float:
        """Fewest right-hand-side evaluations an explicit method needs for stability alone."""
        m = method(name)
        return m.evals_per_step * self.indicator / m.stability_radius


def fastest_mode_connector(lin: Linearisation, lay: Layout) -> int:
    """The connector holding the largest share of the fastest undamped mode's strain energy. In connector space the
    modes are the eigenvectors u of sqrt(k) R J^-1 R^T sqrt(k) (delta = u / sqrt(k)), so connector c's share of a
    mode's strain energy k_c delta_c^2 / 2 is u_c^2."""
    k = np.clip(np.asarray(lin.stiffness, dtype=float), 0.0, None)
    R = speed_map(lay)
    if not k.size or not R.size:
        return 0
    sq = np.sqrt(k)
    M = R @ np.diag(1.0 / np.asarray(lay.inertias[lay.state.first_free:])) @ R.T
    _, u = np.linalg.eigh(sq[:, None] * M * sq[None, :])
    return int(np.argmax(u[:, -1] ** 2))


def element_name(lay: Layout, c: int) -> str:
    """A connector in a message's words: "mesh stage k" for a stage's mesh, else "the <label>" ("the input
    coupling", "shaft 2", "the stage 1 planet 2 ring mesh")."""
    x = lay.connectors[c]
    return f"mesh stage {x.index + 1}" if x.role == "mesh" else x.label if x.role == "shaft" else f"the {x.label}"


def stiffness_keys(lay: Layout, c: int) -> str:
    """What sets a connector's stiffness, in the design file's words, for a message's "check ..."."""
    x = lay.connectors[c]
    if x.role == "shaft":
        return f"the stiffness of shaft {x.index + 1} (stage[{x.index}].shaft.stiffness_Nm_rad)"
    if x.label in ("input coupling", "load coupling"):
        side = x.label.split()[0]
        return f"the stiffness of the {x.label} ({side}.coupling_stiffness_Nm_rad)"
    if x.role in ("mesh", "planet"):
        return f"the contact law of mesh stage {x.index + 1} (stiffness, exponent)"
    return f"the stiffness of the {x.label}"


def _self_exciting(lay: Layout, spec: ModelSpec) -> np.ndarray:
    """Per connector: an element whose force law makes its own harmonics (a mesh: Hertzian, time-varying,
    backlash)."""
    return np.array([x.element.self_exciting(x.params) for x in lay.connectors], dtype=bool)


def _ramp_excitation(spec: ModelSpec, omega: float) -> float:
    """Residual vibration a STEP ramp of T_r leaves in a mode of omega, relative: 6/(omega T_r)^2, 1 if T_r = 0."""
    drive_value = spec.drive.speed_rad_s if spec.drive.kind == "speed" else spec.drive.torque_Nm
    drive_ramp = spec.drive.ramp_s
    motor = spec.drive.motor
    if spec.drive.kind == "motor" and motor is not None:  # a start: the motor's torque, over its own ramp if any
        drive_value = motor.peak_torque_Nm
        drive_ramp = motor.start_parameters[0] if motor.starting in ("soft_start", "vfd") else 0.0
    out = 0.0
    for ramp, value in ((drive_ramp, drive_value), (spec.load.ramp_s, spec.load.torque_Nm)):
        if value != 0:
            out = max(out, 1.0 if ramp <= 0 else min(1.0, 6.0 / (omega * ramp) ** 2))
    return out


def vibration_radians(spec: ModelSpec, lay: Layout, lin: Linearisation, duration_s: float, rtol: float) -> float:
    """P: the largest omega_j min(T, 5/sigma_j) over the excited modes of the linearised chain (module text)."""
    first = 1 if lay.speed_drive else 0
    if lay.n_bodies - first < 1:
        return 0.0
    best = 0.0
    for omega, share, sigma in _chain_modes(lay, spec, lin):
        if share < SELF_EXCITING_SHARE and _ramp_excitation(spec, omega) < rtol:
            continue
        span = duration_s if sigma <= 0 else min(duration_s, DECAY_TIMES / sigma)
        best = max(best, omega * span)
    return best


def _chain_modes(lay: Layout, spec: ModelSpec, lin: Linearisation) -> tuple[tuple[float, float, float], ...]:
    """Per elastic mode of the linearised chain (ascending eigenvalue order): its omega, the self-exciting
    connectors' share of its strain energy and its decay rate sigma, for :func:`vibration_radians` (which adds
    what depends on the run: the ramps, rtol, the duration). Kept for the last few exact inputs (the chain's speed
    map, inertias, self-exciting connectors and the linearisation's stiffness and damping): the points of a speed
    sweep linearise the same chain at the same full load, the same numbers."""
    R, J, inv_sqrt, exciting = _chain(lay, spec)
    k, c = np.asarray(lin.stiffness, dtype=float), np.asarray(lin.damping, dtype=float)
    key = (R.shape, R.tobytes(), J.tobytes(), exciting.tobytes(), k.tobytes(), c.tobytes())
    found = _CHAIN_MODES.get(key)
    if found is not None:
        return found
    w2, u = np.linalg.eigh(inv_sqrt[:, None] * (R.T @ (k[:, None] * R)) * inv_sqrt[None, :])
    phi = inv_sqrt[:, None] * u
    top = max(float(np.max(np.abs(w2))), np.finfo(float).tiny)
    out = []
    for j in range(w2.size):
        if w2[j] <= 1e-9 * top:
            continue
        omega = math.sqrt(w2[j])
        d = R @ phi[:, j]
        strain = k * d**2
        share = float(strain[exciting].sum() / strain.sum()) if strain.sum() > 0 else 0.0
        sigma = float(c @ d**2) / (2.0 * float(J @ phi[:, j] ** 2))
        out.append((omega, share, sigma))
    return remember(_CHAIN_MODES, key, tuple(out))


_CHAIN_MODES: dict[tuple, tuple[tuple[float, float, float], ...]] = {}  # _chain_modes by its exact inputs


def _chain(lay: Layout, spec: ModelSpec) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The speed map R of the free bodies, their inertias J, 1/sqrt(J) and the self-exciting connectors of
    :func:`vibration_radians`: the layout's own, kept with it (every run of a model chooses again)."""
    cache = lay.__dict__.setdefault("_choice_chain", [])
    if not cache:
        first = 1 if lay.speed_drive else 0
        J = np.asarray(lay.inertias[first:], dtype=float)
        cache.append((speed_map(lay, range(first, lay.n_bodies)), J, 1.0 / np.sqrt(J), _self_exciting(lay, spec)))
    return cache[0]


def model_size(lay: Layout, spec: ModelSpec) -> ModelSize:
    """The model's size as the price per evaluation sees it (:class:`gearcli.core.cost.ModelSize`; kept with the
    layout)."""
    cache = lay.__dict__.setdefault("_model_size", [])
    if not cache:
        cache.append(_model_size(lay, spec))
    return cache[0]


def _model_size(lay: Layout, spec: ModelSpec) -> ModelSize:
    meshes = [x for x in lay.connectors if x.role in ("mesh", "planet")]

    def mesh(x) -> object:
        return spec.meshes[x.index] if 0 <= x.index < len(spec.meshes) else None

    def harmonic(m) -> bool:
        return m is not None and (any(m.transmission_error_m) or any(m.stiffness_harmonics))

    return ModelSize(states=lay.state.n_states, meshes=len(meshes), planet_meshes=sum(x.role == "planet" for x in meshes),
                     time_varying=sum(bool(getattr(mesh(x), "time_varying", False)) for x in meshes),
                     harmonics=sum(harmonic(mesh(x)) for x in meshes),
                     motor=lay.drive.motor is not None)


def sign_flips(lay: Layout) -> str:
    """Why an explicit method cannot run the scene: a lossy element whose vibration speed exceeds its nominal
    pitch-line speed (:func:`gearcli.model.assembly.loss_speeds`) has its power-flow sign reversed by the run-up's
    vibration, each reversal a switch of (1 - eta) of its force within a small part of that speed, which an explicit
    method resolves step by step at every crossing (a one-stage scene at 0.003 rpm: DOP853 stopped after 3.4e6
    evaluations at 0.12 s of 0.3 s) while Radau steps through it on its Jacobian (1.5e4). "" when none does."""
    for x in lay.connectors:
        if x.lossy:
            _, v, v_vib = loss_speeds(lay.spec, lay.bodies, x)
            if v_vib > v:
                return (f"the {x.label}'s power-flow sign flips with its vibration ({v_vib:.2g} m/s against its "
                        f"{v:.2g} m/s pitch-line speed), every flip a step an explicit method must resolve")
    return ""


def _explicit_refused(indicator: float) -> bool:
    """An explicit run whose stability alone exceeds the explicit budget would be refused (guards)."""
    m = method(EXPLICIT_METHOD)
    return m.evals_per_step * indicator / m.stability_radius > EXPLICIT_CAP


def _input_angle(spec: ModelSpec, t: float) -> float:
    """The input's angle at t from its STEP speed profile (a torque drive at its nominal speed likewise)."""
    v, T = abs(spec.drive.speed_rad_s), spec.drive.ramp_s
    if T <= 0:
        return v * t
    if t < T:
        s = t / T
        return v * T * s**3 * (1 - 0.5 * s)
    return v * (t - 0.5 * T)


def excited_radians(spec: ModelSpec, lay: Layout, duration_s: float) -> float:
    """E: the largest phase the highest harmonic of any excitation sweeps over the run (module text)."""
    theta = _input_angle(spec, duration_s)
    best = 0.0
    for k, c in enumerate(lay.stage_conn):
        m = spec.meshes[k]
        harmonics = max(len([e for e in m.transmission_error_m if e]), len([s for s in m.stiffness_harmonics if s]),
                        int(m.time_varying))
        if harmonics:
            best = max(best, harmonics * m.pinion_teeth * abs(lay.bodies[lay.connectors[c].a].ratio) * theta)
    for amplitude, order in spec.drive.ripple:
        if amplitude:
            best = max(best, abs(order) * theta)
    if spec.load.torque_Nm:
        for amplitude, frequency in spec.load.fluctuation:
            if amplitude:
                best = max(best, 2 * math.pi * abs(frequency) * duration_s)
    return best


def predicted_costs(indicator: float, vibration_rad: float, excited_rad: float = 0.0, rtol: float = 1e-6,
                    engines: dict[str, dict[str, float]] | None = None,
                    work_factor: float = 1.0, size: ModelSize | None = None, *,
                    radau_floor: float = 0.0) -> tuple[tuple[float, float],
                                                                             tuple[float, float], tuple[str, str],
                                                                             tuple[float, float]]:
    """((DOP853, Radau) evaluations, (DOP853, Radau) predicted wall seconds, the engine each is priced on, and
    the part of each wall time that is loading the engine). ``engines``: per method, the engines that may run
    it and what loading each still costs this process (default: Python only); ``work_factor``: the integrations
    of the whole run over the run's own (its check pass, ``cost.CHECK_PASS_WORK``), weighed against the load;
    ``size``: the model's, for the price per evaluation (:func:`gearcli.core.cost.price_us_per_eval`);
    ``radau_floor``: the least evaluations Radau's step ceiling (:func:`contact_step`) leaves it."""
    dop, radau = predicted_evaluations(indicator, vibration_rad, excited_rad, rtol)
    nfev = (dop, max(radau, radau_floor))
    walls, names, loads = [], [], []
    for name, n in zip((EXPLICIT_METHOD, IMPLICIT_METHOD), (x * work_factor for x in nfev), strict=True):
        options = (engines or {}).get(name) or {"python": 0.0}
        loaded = {e: predicted_wall_s(e, name, n, 0.0, size) for e in options}  # as if loaded: no load dependence
        best = min(options, key=loaded.__getitem__)
        walls.append(loaded[best] if options[best] == 0.0 else predicted_wall_s(best, name, n, options[best], size))
        names.append(best)
        loads.append(options[best])
    return nfev, (walls[0], walls[1]), (names[0], names[1]), (loads[0], loads[1])


_FULL_LOAD: list[tuple[ModelSpec, Layout, np.ndarray, Linearisation]] = []  # the last scene's (one entry)


def _at_full_load(spec: ModelSpec, layout: Layout | None = None) -> tuple[Layout, np.ndarray, Linearisation]:
    """The scene's layout, static connector forces and linearisation at full load: the same for every run of one
    model (a sweep point's settle runs and periodic search choose again with other durations), kept for the last
    scene asked. ``layout``: the scene's, when the caller has it (the model's), else built from ``spec``."""
    if _FULL_LOAD and _FULL_LOAD[0][0] is spec:
        return _FULL_LOAD[0][1:]
    lay = layout if layout is not None and layout.spec is spec else Layout.of(spec)
    static = static_forces(lay)
    entry = (spec, lay, static, linearise(lay, operating_forces(lay)))  # planets at their settled shares
    _FULL_LOAD[:] = [entry]
    return entry[1:]


def stability_step(spec: ModelSpec, layout: Layout, name: str) -> float:
    """The step ceiling of an explicit method ``name`` on the scene (s): its stability radius along the imaginary axis
    over the largest |lambda| of the scene linearised at full load, where its stiffest mode sits at rest (math.inf
    for an implicit method, or a scene without a stiff mode). A step beyond it amplifies that mode (DOP853 at h |lambda|
    = 12: ~5e3-fold a step, at 120: 3e15-fold); the error estimate rejects such a step only once the mode carries
    more than the tolerance, so a run that starts at rest in the mode (a sweep point continued from its
    neighbour's equilibrium) took them undetected, and DOP853's dense output between two such accepted steps
    swung by the amplified mode (docs/numerics.md "The step ceiling"); at a loose rtol, where the tolerance lets
    the mode grow further, a run-up peak came out many times the true one. Where the mode is excited, the error
    control keeps the steps below the ceiling anyway. A run whose steps the ceiling sets is refined by halving the
    ceiling, not by a tighter rtol: its check pass does both (:data:`gearcli.simulate.estimate.CHECK_CEILING`)."""
    m = method(name)
    if m.implicit:
        return math.inf
    lam = _at_full_load(spec, layout)[2].max_abs_eigenvalue
    return m.stability_radius / lam if lam > 0 and math.isfinite(lam) else math.inf


#: an implicit method's steps (at most) over the shortest stretch between two kinks of a time-varying contact length
CONTACT_STEPS = 2.0
#: the least stretch counted, in mesh cycles (a shorter one, from a contact ratio within 1/64 of a whole number,
#: changes the stiffness over so short a phase that it does not set the steps)
MIN_STRETCH = 1.0 / 64.0


def contact_step(lay: Layout) -> float:
    """An implicit method's step ceiling on a scene with a time-varying contact length (``[contact] time_varying``):
    :data:`CONTACT_STEPS` steps over the shortest stretch between two kinks of any such mesh's L(phi)
    (:func:`gearcli.model.contact_lines.shortest_stretch`) at its steady mesh period; inf without one. Radau's three
    collocation nodes may all fall on one side of a step in the stiffness: a spur pair at 6 rpm (2 Hz mesh, the
    single-pair stretch 0.19 s) was stepped over in 0.5 s steps that never met the single-pair stiffness, the
    window mean F_t 9.5 % low (1293.6 N against the static 1428.6 N), where DOP853's error control sees it."""
    from gearcli.simulate.periodic import steady_input_speed_rad_s  # lazy: periodic integrates with this module

    if not any(x.element.NAME == "mesh" and x.params[mesh.I_TV] != 0.0 for x in lay.connectors):
        return np.inf
    w_in = abs(steady_input_speed_rad_s(lay))
    ceiling = np.inf
    for x in lay.connectors:
        if x.element.NAME != "mesh" or x.params[mesh.I_TV] == 0.0 or w_in == 0.0:
            continue
        stretch = max(shortest_stretch(x.params[mesh.I_EA], x.params[mesh.I_EB]), MIN_STRETCH)
        period = mesh.cycle_period_s(x.params, lay.bodies[x.a].ratio * w_in)
        if np.isfinite(period) and period > 0.0:
            ceiling = min(ceiling, period * stretch / CONTACT_STEPS)
    return ceiling


#: Radau's right-hand-side evaluations per accepted step where its steps are set by :func:`contact_step` (measured
#: 9.8 on a slow spur pair; its Newton iterations of three stages and the step's own evaluation)
CONTACT_EVALS_PER_STEP = 8.0


def _at_operating_point(lay: Layout, operating: np.ndarray) -> Linearisation:
    """The linearisation at the run-up forces ``operating`` (time-varying stiffness at its stiffest phase), kept
    with the layout for the last few operating points: a model's runs past its ramps (a sweep point's settle runs)
    share one."""
    cache = lay.__dict__.setdefault("_operating_points", {})
    key = operating.tobytes()
    if key not in cache:
        if len(cache) >= 8:
            cache.pop(next(iter(cache)))
        cache[key] = linearise(lay, operating, stiffest_phase=True)
    return cache[key]


def _priced(nfev: float, wall_s: float, engine: str, load_s: float) -> str:
    """One method's prediction in the choice's words: its evaluations and time on the engine it is priced on, the
    engine's load (which the choice leaves aside) named apart."""
    load = f", +{load_s:.2g} s to load it" if load_s > 0 else ""
    return f"{nfev:.2g} evaluations ~{wall_s - load_s:.2g} s ({engine}{load})"


def choose_method(spec: ModelSpec, duration_s: float, requested: str, rtol: float = 1e-6,
                  engines: dict[str, dict[str, float]] | None = None, work_factor: float = 1.0, *,
                  layout: Layout | None = None) -> Choice:
    """The method to run and why (``requested`` other than "auto" is kept, with the indicator). ``engines``:
    per method, the engines that may run it and their remaining load cost (:func:`predicted_costs`;
    :func:`gearcli.engine.options`); ``layout``: the scene's (the model's), not built again."""
    lay, static, full = _at_full_load(spec, layout)
    op = _at_operating_point(lay, np.maximum(np.abs(static), peak_rigid_forces(lay, duration_s)))
    lam = max(full.max_abs_eigenvalue, op.max_abs_eigenvalue)
    low = min((x for x in (full.min_abs_eigenvalue, op.min_abs_eigenvalue) if x > 0), default=0.0)
    indicator = lam * duration_s
    ratio = lam / low if low > 0 else math.inf
    lin = op if bool(np.any(full.stiffness == 0.0)) else full
    vib = vibration_radians(spec, lay, lin, duration_s, rtol)
    exc = excited_radians(spec, lay, duration_s)
    size = model_size(lay, spec)
    ceiling = contact_step(lay)  # Radau's steps on a time-varying contact length: at least duration / ceiling
    floor = duration_s / ceiling * CONTACT_EVALS_PER_STEP if math.isfinite(ceiling) else 0.0
    nfev, walls, on, loads = predicted_costs(indicator, vib, exc, rtol, engines, work_factor, size, radau_floor=floor)
    summary = f"max|λ|·T = {indicator:.3g}"
    costs = f"predicted DOP853 {_priced(nfev[0], walls[0], on[0], loads[0])}, Radau {_priced(nfev[1], walls[1], on[1], loads[1])}"
    why = f"{summary}, {vib:.3g} rad of excited vibration, {exc:.3g} rad of excitation: {costs}"
    barred = sign_flips(lay)
    explicit = walls[0] - loads[0] <= IMPLICIT_MARGIN * (walls[1] - loads[1]) and not _explicit_refused(indicator) \
        and not barred
    pick = EXPLICIT_METHOD if explicit else IMPLICIT_METHOD  # auto's, whatever was requested
    if requested != AUTO:
        chosen, reason = requested, f"as requested ({summary})"
    elif explicit:
        chosen, reason = pick, f"{why}: explicit {pick}"
    else:
        chosen, reason = pick, f"{why}: implicit {pick} with the analytic Jacobian" + (f" ({barred})" if barred else "")
    return Choice(chosen, requested, reason, indicator, ratio, full, op, spec, lay,
                  vib, nfev, exc, walls, on, size, barred if requested == AUTO else "", pick)
