"""What ``simulate`` returns: the result of a run (its time series, statistics per stage, the solver's and the
energy balance's figures, the steady state's, the bearings' window statistics).

Produced by the simulate layer, read by the layers above (report, sweep, life, io, api). The per-stage
statistics (``StageDynamics`` and its ``ChannelStats``) stay in :mod:`gearcli.results`: the design's
simulated-K_v re-rating (``design.simulated``) reads them.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, NotRequired, TypedDict

from gearcli.core.channels import Channel
from gearcli.core.jsontypes import JsonObject
from gearcli.results import ChannelStats, StageDynamics

if TYPE_CHECKING:
    import numpy as np

    from gearcli.diagnostics import Diagnostic


@dataclass(frozen=True)
class SolverStats:
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


@dataclass(frozen=True)
class EnergyBalance:
    """Energies in J over the run; residual = input - load - damping - kinetic - potential."""

    input_work_J: float
    load_work_J: float
    damping_loss_J: float
    kinetic_change_J: float
    potential_change_J: float
    residual_relative: float


@dataclass(frozen=True)
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


class BearingStats(TypedDict):
    """One bearing's reactions over the steady window (``[[bearing]]`` tables, docs/life.md)."""

    shaft: int  # 1-based; 0 for a planet pin's bearing
    planet_stage: NotRequired[int]  # a planet pin's bearing: its planetary stage, 1-based
    position_mm: float
    radial_N: ChannelStats
    axial_N: ChannelStats
    static_safety_min: NotRequired[float | None]  # ISO 76 s_0 at the window's peak P_0 (with static_load_rating_kN)


class SimulationExtra(TypedDict, total=False):
    """What a simulation reports besides its fields: the parametric work of time-varying meshes, auto's
    stiffness indicator, the natural frequencies at the operating point of the run-up, a motor's summary
    (docs/output.md ``summary.motor``), the bearings' window statistics."""

    parametric_work_J: float
    stiffness_indicator: float
    natural_frequencies_runup_Hz: list[float]
    motor: dict[str, float | None]
    bearings: list[BearingStats]


@dataclass(frozen=True)
class SimulationResult:
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
