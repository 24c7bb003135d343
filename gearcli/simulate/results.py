"""What ``simulate`` returns: the result of a run (its time series, statistics per stage, the solver's and the
energy balance's figures, the steady state's, the bearings' window statistics).

Produced by the simulate layer, read by the layers above (report, sweep, life, io, api); the design's
simulated-K_v re-rating (``design.iso6336``) reads the per-stage statistics by their fields, without
importing them. The design's own results are :mod:`gearcli.results`.
"""

from __future__ import annotations

from dataclasses import field
from typing import TYPE_CHECKING, NotRequired, TypedDict

from gearcli.core.channels import Channel
from gearcli.core.jsontypes import JsonObject
from gearcli.core.records import record
from gearcli.results import MeshStiffness, RatedMesh

if TYPE_CHECKING:
    import numpy as np

    from gearcli.diagnostics import Diagnostic
    from gearcli.simulate.planet_results import PlanetDynamics, PlanetMeshDynamics  # noqa: F401 - re-exported

#: the planetary stage's planet results, in :mod:`gearcli.simulate.planet_results` (a parallel file never creates
#: them) and importable from here by name (:func:`__getattr__`)
PLANETARY = ("PlanetDynamics", "PlanetMeshDynamics")


@record
class ChannelStats:
    """A channel's statistics over the steady window."""

    mean: float
    min: float
    max: float
    std: float


@record
class StatisticsError:
    """Estimated error of one stage's window statistics of F_t (absolute, N), from the check pass
    (gearcli.simulate.estimate); radial and axial forces share the relative error."""

    stage: int  # 1-based
    reference_N: float  # the force the target refers to: |mean F_t| (static |F_t| when the mean is 0)
    target_relative: float
    tangential_N: ChannelStats  # estimated error of mean, min, max, std: |check - run| / (CHECK_FACTOR - 1)
    spectrum_N: float  # largest amplitude difference over the F_t spectrum (Hann, detrended)
    relative: dict[str, float]  # mean, min, max, std, spectrum: error / reference_N
    dominant_frequency_Hz: float  # of the run
    check_dominant_frequency_Hz: float  # of the check pass
    unresolved: tuple[str, ...]  # statistics beyond the target
    suggested_rtol: float | None  # simulation.rtol that would resolve them (None when resolved, or when none down to
    # the schema's floor is predicted to: estimate.suggested_rtol)
    resolved: bool = True  # no statistic beyond the target (the solver's and the sampling's errors together)
    mean_target_relative: float = 1e-4  # the mean's target (target_relative is that of min, max, std, spectrum)
    # the output sampling's share of min and max (gearcli.simulate.sampling), added to the solver's above for
    # ``unresolved`` and ``resolved``: the sampling estimate's {min, max} in N and over reference_N, their sum with
    # the solver's, and the simulation.steps that would resolve it (None when the sampling is resolved or the
    # schema's maximum cannot)
    sampling_N: dict[str, float] = field(default_factory=dict)
    sampling_relative: dict[str, float] = field(default_factory=dict)
    total_relative: dict[str, float] = field(default_factory=dict)
    suggested_steps: int | None = None
    # the start-up transient the settle test fitted in the window (gearcli.simulate.leftover): its error of the mean
    # and bound on that of {min, max, std} in N and over reference_N, added to total_relative (empty: a periodic
    # state, no fit)
    transient_N: dict[str, float] = field(default_factory=dict)
    transient_relative: dict[str, float] = field(default_factory=dict)


@record
class SamplingError:
    """Estimated error of one stage's window min, max and mean of F_t from the output sampling alone (the peaks
    between samples, the integral's rule: gearcli.simulate.sampling), computed for every run (no integration)."""

    min_N: float
    max_N: float
    relative: dict[str, float]  # min, max, mean, std over reference_N
    reference_N: float  # as StatisticsError.reference_N: |mean F_t| (static |F_t| when the mean is 0)
    target_relative: float  # 1e-3 (with the solver's estimate where a check pass ran)
    samples: int  # window samples
    resolved: bool  # the sampling's share, with the solver's where a check pass ran, within the target
    suggested_steps: int | None  # simulation.steps that resolves it (None: resolved, or beyond the schema's maximum)
    steps_cap: int  # the schema's maximum of simulation.steps
    mean_N: float = 0.0  # the mean's: |T_h - T_2h| / 3 of the trapezoid rule (0 for a periodic window)
    std_N: float = 0.0  # the std's: its larger change over the even or odd samples (0 for a periodic window)
    # a mode or excitation line above the samples' Nyquist frequency that carries force in the window
    # (gearcli.simulate.aliasing): min_N and max_N are then no bound. None: none found
    aliased: JsonObject | None = None


@record
class DteStats:
    """Dynamic transmission error q = delta - e over the statistics window, um (``rms`` about the mean)."""

    mean: float
    rms: float
    min: float
    max: float


#: Impact regimes of a mesh over the statistics window (the loaded flank: the one the static load presses)
REGIME_NO_IMPACT = "no impact"  # never out of contact (a mesh without backlash may pass to its back flank)
REGIME_SINGLE_SIDED = "single-sided impact"  # it loses contact but never touches the other flank
REGIME_DOUBLE_SIDED = "double-sided impact"  # it also strikes the other (back) flank


@record
class StageDynamics:
    """One stage's simulated forces over the steady window, its run peak and mesh response."""

    index: int  # 1-based
    tangential_N: ChannelStats  # over the steady window
    radial_N: ChannelStats
    axial_N: ChannelStats
    penetration_mm: ChannelStats
    static_tangential_N: float  # the design's static F_t at full load
    peak_tangential_N: float  # largest |F_t| over the whole run (run-up included)
    peak_time_s: float
    dynamic_factor: float | None  # steady-window max |F_t| / |simulated static F_t|; None when that static is 0
    error_estimate: StatisticsError | None = None  # None when no refinement pass ran
    mesh_stiffness: MeshStiffness | None = None
    # mesh response over the statistics window (issue 13); defaults for hand-made results
    dte_um: DteStats | None = None
    contact_loss_fraction: float = 0.0  # time fraction with zero mesh force
    back_flank_fraction: float = 0.0  # time fraction in contact on the flank opposite the loaded one
    regime: str = ""  # REGIME_*
    rating: RatedMesh | None = None  # [rating] dynamic_factor = "simulated": the rating at the simulated K_v
    # issue 21: the run-up overshoot apart from the steady dynamic factor; defaults for hand-made results
    runup_factor: float | None = None  # whole-run peak |F_t| / |simulated static F_t|
    simulated_static_tangential_N: float | None = None  # static F_t of the load the simulation applies, with
    # the losses its dynamics model (the stage efficiencies): the reference of both factors
    # a planetary stage (issue 25): every planet's sun and ring mesh; the largest planet's window-mean sun-mesh
    # |F_t| over the mean planet's (the sun torque's share) (the stage's own fields are planet 1's sun mesh)
    planets: tuple[PlanetDynamics, ...] = ()
    load_sharing_factor: float | None = None
    # [rating] dynamic_factor = "simulated" on a planetary stage: its planet–ring mesh rated at the ring meshes'
    # own simulated K_v (``rating`` is the sun–planet mesh's, at the sun meshes' K_v)
    planet_ring_rating: RatedMesh | None = None
    planet_ring_mesh_stiffness: MeshStiffness | None = None  # a planetary stage's planet–ring law (mesh_stiffness:
    # its sun–planet mesh's)
    # the stage's kind (the design file's stage ``type``, ``ModelSpec.stage_types``): its output facet names
    # the statistics (a belt's span force and stretch); not a JSON key of a gear stage
    type: str = "parallel"
    # the window min/max's error from the output sampling (every run; error_estimate adds it to the solver's)
    sampling_error: SamplingError | None = None


@record
class SolverStats:
    """What the integration did: method, tolerances, evaluations, steps, time and status."""

    method: str  # the scipy method that ran
    requested_method: str  # as in the design file ("auto" ...)
    choice_reason: str  # why auto chose it, or "as requested"
    rtol: float
    atol: dict[str, float]  # per state group: {"deflection_m": ..., "speed_rad_s": ...}
    nfev: int
    njev: int
    nlu: int
    steps: int  # accepted integrator steps
    wall_s: float  # integration only, excluding imports and model assembly
    energy_residual: float  # (W_in - W_load - E_damp - dKE - dPE) / max(|W_in|, |W_load|, KE_end)
    status: int  # solve_ivp status (0: reached the end)
    message: str
    check_pass: JsonObject | None = None  # the error-estimate pass: rtol, from_s, nfev, njev, steps, wall_s, finished
    engine: str = "python"  # "python" (scipy) or "compiled" (gearcli.engine)
    engine_reason: str = "as requested"  # why this engine ran (auto's rule, or what sends a scene to Python)
    compile_s: float = 0.0  # loading (or compiling) the compiled engine in this process; not in wall_s
    #: what auto's cost model predicted for the run's integration: nfev, price_us_per_eval, wall_s (docs/output.md)
    prediction: JsonObject | None = None
    #: where an auto run re-decided mid-run: [{at_s, from, to, why}] (gearcli.simulate.course)
    course_changes: tuple[JsonObject, ...] = ()
    #: what the whole result cost (gearcli.simulate.spent): the evaluations and integration seconds of every run
    #: behind it, this one and those it replaced with their check passes, its own check pass aside (check_pass);
    #: and how many runs (1: this one alone). Not given: this run's own nfev and wall_s
    total_nfev: int = -1
    total_wall_s: float = -1.0
    runs: int = 1

    def __post_init__(self) -> None:  # a run alone cost what it took (object.__setattr__: the record is frozen)
        if self.total_nfev < 0:
            object.__setattr__(self, "total_nfev", self.nfev)
        if self.total_wall_s < 0.0:
            object.__setattr__(self, "total_wall_s", self.wall_s)


@record
class EnergyBalance:
    """Energies in J over the run; residual = input - load - damping - kinetic - potential + parametric, the
    parametric work the work a time-varying mesh stiffness does on its spring beyond its potential (K' p^2 / 2 for
    a linear law; 0 without time-varying meshes), so that the record's terms close on their own."""

    input_work_J: float
    load_work_J: float
    damping_loss_J: float
    kinetic_change_J: float
    potential_change_J: float
    residual_relative: float
    parametric_work_J: float = 0.0


@record
class SteadyState:
    """How the statistics window was found (``[simulation] steady``).

    ``mode = "window"``: the fixed window (``period_s`` the excitation period for information, the rest
    None). ``mode = "periodic"``: the run went period by period past the ramps until the state at the
    period boundaries repeated (Poincare map) within the run's tolerance; ``periodicity`` is "period-1",
    "period-k" (a subharmonic: the state repeats after k periods) or "none" (no repeat up to the cap);
    ``residual`` the last boundary mismatch in units of the tolerance (converged when <= 1).
    """

    mode: str  # "window" | "periodic"
    period_s: float | None  # the common period of the excitations at the steady operating speed
    periods_to_converge: int | None  # excitation periods integrated past the ramps until the repeat
    periodicity: str | None  # "period-1" | "period-k" | "none"
    converged: bool | None
    residual: float | None
    period_source: str = ""  # how period_s was formed (the excitations, or why the slowest one was taken)
    window_periods: int | None = None  # whole excitation periods in the statistics window
    samples_per_period: int | None = None
    cap_periods: int | None = None
    # how the periodic orbit was found (gearcli.simulate.shooting): "shooting" (Newton on the period map) or
    # "brute force" (period by period until it repeats); Newton steps; the monodromy matrix's source; the
    # Floquet multipliers ((re, im), largest modulus first), stability and the bifurcation nearby ("none",
    # "fold", "period doubling"); why shooting fell back to brute force, where it did
    method: str | None = None
    iterations: int | None = None
    attempts: int | None = None  # Newton starts (a restart follows more brute-force periods)
    monodromy: str | None = None
    multipliers: tuple[tuple[float, float], ...] | None = None
    spectral_radius: float | None = None
    stable: bool | None = None
    bifurcation: str | None = None
    note: str = ""
    # issue 30: the window shown settled (gearcli.simulate.settle): no start-up transient left at its start
    # (a fixed window), or a converged periodic state; the largest fitted transient there (of the static force),
    # the time from which it would be settled, and the runs the window was moved later for it
    settled: bool | None = None
    transient_fraction: float | None = None
    settle_time_s: float | None = None
    settle_runs: int = 0


class BearingStats(TypedDict):
    """One bearing's reactions over the steady window (``[[bearing]]`` tables, docs/life.md)."""

    shaft: int  # 1-based; 0 for a planet pin's bearing
    planet_stage: NotRequired[int]  # a planet pin's bearing: its planetary stage, 1-based
    position_mm: float
    radial_N: ChannelStats
    axial_N: ChannelStats
    static_safety_min: NotRequired[float | None]  # ISO 76 s_0 at the window's peak P_0 (with static_load_rating_kN)


class StartSummary(TypedDict):
    """``summary.start``: per stage, the run's peak |F_t| over the rigid-body start's, and that rigid peak (N)."""

    peak_over_rigid: list[float | None]
    rigid_peak_N: list[float]


class SimulationExtra(TypedDict, total=False):
    """What a simulation reports besides its fields: the parametric work of time-varying meshes, auto's
    stiffness indicator, the natural frequencies at the operating point of the run-up, a motor's summary
    (docs/output.md ``summary.motor``), the bearings' window statistics."""

    parametric_work_J: float
    stiffness_indicator: float
    natural_frequencies_runup_Hz: list[float]
    damped_modes: list[tuple[float, float]]  # (f_d Hz, ζ) of the run's damped eigenvalues (Choice.run_eigenvalues)
    motor: dict[str, float | None]
    bearings: list[BearingStats]
    start: StartSummary  # the run's peak over the rigid-body start's (issue 30)


@record
class SimulationResult:
    """One simulation: the series, the window's statistics per stage, the solver and the energy."""

    time_s: np.ndarray
    series: dict[Channel, np.ndarray]  # what it measures -> samples in SI, in output order (io.channels names them)
    window_s: tuple[float, float]
    ratio: float  # dynamic ratio mean(omega_in) / mean(omega_out) over the window
    output_speed_deg_s: float  # mean over the window
    input_speed_deg_s: float  # mean over the window
    stages: tuple[StageDynamics, ...]
    solver: SolverStats
    energy: EnergyBalance
    warnings: tuple[str, ...] = field(default_factory=tuple)
    natural_frequencies_Hz: tuple[float, ...] = field(default_factory=tuple)  # linearised, at full load
    extra: SimulationExtra | None = None
    diagnostics: tuple[Diagnostic, ...] = field(default_factory=tuple)  # warnings are their messages
    natural_frequencies_boundary: str = "clamped_input"  # "clamped_input" (speed drive) or "free" (torque drive)
    final_state: np.ndarray | None = None  # state vector at the end of the run (model layout), for continuation
    final_time_s: float | None = None  # time of final_state (a periodic steady state may end before duration_s)
    steady: SteadyState | None = None  # how the window was found ([simulation] steady)
    units: tuple[str, str] = ("deg_s", "Nmm")  # output speed and torque units: the design file's key suffixes
    # (io.units.key_units, set by the facade gearcli.api)


def __getattr__(name: str) -> object:
    if name in PLANETARY:
        from gearcli.simulate import planet_results  # lazy: a file without planetary stages never needs them

        return getattr(planet_results, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
