"""Frozen result objects of ``gearcli report``: theory against simulation, spectra, accuracy study.

The report layer computes; ``gearcli.io`` formats. Stage indices are 1-based (``None`` for rows that
belong to the whole train), and quantity names carry their units as in the JSON output.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from gearcli.core.records import record
from gearcli.results import DesignResult
from gearcli.simulate.results import ChannelStats, SimulationResult

if TYPE_CHECKING:
    from gearcli.model.campbell import CampbellData
    from gearcli.model.modes import ModalAnalysis


# ------------------------------------------------------------------------------ theory vs simulation
@record
class ComparisonRow:
    """One design (static) value against the simulated mean over the steady window.

    ``error_percent`` is signed, ``100 (simulated - theory) / |theory|``; ``None`` when theory is 0, or when it is a state the run
    never reaches (:attr:`TheoryPoint.reached` False).
    """

    stage: int | None  # None: a train-level row
    quantity: str  # "ratio", "input_speed_deg_s", "output_speed_deg_s", "tangential_N", ...
    theory: float
    simulated: float
    error_percent: float | None


@record
class TheoryPoint:
    """Where the comparison's theory is taken when the drive does not prescribe the speed: the train's steady
    operating point (a motor's stable crossing of its curve with the load reflected to it, a torque drive's balance
    with a speed-dependent load, :func:`gearcli.model.damping.operating_speed_rad_s`), not the design's nominal
    speed. The theory speeds are the design's scaled to it, the theory forces the design's times ``load_factor``
    (the load law's torque there over its nominal torque): what the train settles at, so the error column shows
    the simulation's departure from the steady state, not the motor's slip off its nameplate."""

    drive: str  # "motor" | "torque"
    input_speed_deg_s: float  # the operating point's input speed
    nominal_input_speed_deg_s: float  # the design's (the file's [input] speed)
    load_factor: float  # T_L at the operating point / its nominal torque (1 without a speed law)
    # False: the train settles nowhere (a motor that cannot start or runs away, a torque drive nothing balances):
    # the theory is the design's nominal point, which the run never reaches, and no speed or force error is given
    reached: bool = True

    @property
    def speed_factor(self) -> float:
        return self.input_speed_deg_s / self.nominal_input_speed_deg_s if self.nominal_input_speed_deg_s else 1.0


@record
class MeshOrder:
    """The amplitude of one mesh order (h x the mesh frequency) in a stage's F_t and DTE over the window."""

    order: int  # h = 1, 2, 3 ...
    frequency_Hz: float
    tangential_N: float | None  # None at or above the samples' Nyquist frequency (an alias is no amplitude)
    dte_um: float | None  # None when the result carries no DTE channel, or above Nyquist


@dataclass(frozen=True, eq=False)
class Spectrum:
    """Amplitude spectrum of one stage's detrended F_t over the steady window (Hann window; over a periodic steady
    state's whole periods the plain DFT of F_t less its mean, whose bins are the lines' exact amplitudes).

    ``amplitude_N`` is scaled so that a pure sine of amplitude A shows a peak of A (coherent gain of
    the Hann window removed). ``peak_frequency_Hz`` is the centre of the largest non-DC bin, good to
    ``resolution_Hz`` = 1 / T_window; ``None`` when the force does not fluctuate. ``peak_amplitude_N`` is
    the amplitude of that line wherever it lies between the bins (the windowed transform's maximum next to the
    peak bin), not the bin's value, which Hann scalloping lowers by up to 15 %.
    """

    stage: int
    frequency_Hz: np.ndarray
    amplitude_N: np.ndarray
    peak_frequency_Hz: float | None
    peak_amplitude_N: float
    resolution_Hz: float
    nyquist_Hz: float
    window_s: tuple[float, float]
    mesh_frequency_Hz: float
    matches: str  # what the peak lies next to: "mesh frequency", "natural frequency 2", "none", ...
    mesh_orders: tuple[MeshOrder, ...] = ()  # amplitudes at 1x, 2x, 3x ... the mesh frequency
    whole_periods: bool = False  # the window is whole periods: the plain DFT (no Hann window), every line on a bin


@dataclass(frozen=True, eq=False)
class StageReport:
    """The fluctuation of one mesh over the steady window, its run-up peak and its spectrum."""

    stage: int
    tangential_N: ChannelStats
    radial_N: ChannelStats
    axial_N: ChannelStats
    static_tangential_N: float
    peak_tangential_N: float
    peak_time_s: float
    dynamic_factor: float | None  # steady-window max |F_t| / static; None where the static force is 0
    spectrum: Spectrum
    runup_factor: float | None = None  # whole-run peak |F_t| / static (the start-up overshoot)
    simulated_static_tangential_N: float | None = None  # the factors' reference: static F_t as simulated


# ------------------------------------------------------------------------------- numerical accuracy
QUANTITIES = ("speed", "mean_force", "peak_force")


@record
class RunMetrics:
    """What the accuracy study compares between runs: window-mean output speed, per-stage mean F_t
    and per-stage run-up peak |F_t|."""

    output_speed_deg_s: float
    mean_tangential_N: tuple[float, ...]
    peak_tangential_N: tuple[float, ...]

    @classmethod
    def of(cls, sim: SimulationResult) -> RunMetrics:
        return cls(
            output_speed_deg_s=float(sim.output_speed_deg_s),
            mean_tangential_N=tuple(float(s.tangential_N.mean) for s in sim.stages),
            peak_tangential_N=tuple(float(s.peak_tangential_N) for s in sim.stages),
        )


@record
class ReferenceRun:
    """The tight-tolerance reference and the independent check that bounds its own error.

    ``uncertainty`` is the largest relative difference between the two runs over the three compared
    quantities; ``differences`` gives each, the reference's resolution of that quantity (``resolution``): an error
    of a quantity below its own difference cannot be resolved.
    """

    method: str
    rtol: float
    wall_s: float
    nfev: int
    check_method: str
    check_rtol: float
    check_wall_s: float
    check_nfev: int
    uncertainty: float
    differences: dict[str, float]
    metrics: RunMetrics
    window_s: tuple[float, float] | None = None  # the study's statistics window: the file's, never moved by the settle test

    def resolution(self, quantity: str) -> float:
        """The reference's resolution of one compared quantity: its difference from the check run."""
        return self.differences.get(quantity, self.uncertainty)


@record
class AccuracyRun:
    """One rung of the work-precision ladder, with its errors relative to the reference.

    Errors are relative (not %): speed = |Δ mean ω_out| / |ω_out,ref|; mean_force and peak_force are
    the largest over the stages of |Δ| / |ref|. ``None`` when the run failed (``failure`` says why).
    """

    method: str  # as requested ("auto", "DOP853", ...)
    method_used: str  # the scipy method that ran
    rtol: float
    wall_s: float
    nfev: int
    njev: int
    steps: int
    error_speed: float | None
    error_mean_force: float | None
    error_peak_force: float | None
    below_reference_resolution: dict[str, bool]
    meets_accuracy: bool
    file_settings: bool = False  # the design file's own [simulation] method and rtol
    failure: str | None = None
    engine: str = "python"  # where it ran: "python" (scipy) or "compiled" (gearcli.engine)

    def error(self, quantity: str) -> float | None:
        return getattr(self, f"error_{quantity}")


@record
class AccuracyStudy:
    requested_accuracy: float
    reference: ReferenceRun
    runs: tuple[AccuracyRun, ...]
    recommended: AccuracyRun | None  # cheapest (nfev x the method's median s/eval) meeting the accuracy
    file_settings_meet_accuracy: bool
    notes: tuple[str, ...] = ()
    file_run_extra: bool = False  # the file's own setting is no rung of the ladder: a run of its own, besides it

    @property
    def file_run(self) -> AccuracyRun | None:
        return next((r for r in self.runs if r.file_settings), None)


# ------------------------------------------------------------------------------------ the report
@record
class RatingComparison:
    """One rated stage: ISO 6336-1's K_v (theory) beside the simulated one, with the smallest safeties at each
    (the simulated ones only when ``[rating] dynamic_factor = "simulated"``, else None)."""

    stage: int
    K_v_iso: float
    K_v_iso_source: str  # "iso" | "given"
    K_v_simulated: float  # max(1, steady-window max |F_t| / static F_t)
    min_S_H_iso: float
    min_S_F_iso: float
    min_S_H_simulated: float | None
    min_S_F_simulated: float | None


@dataclass(frozen=True, eq=False)
class Report:
    """Everything ``gearcli report`` shows, for one design file and its own simulation settings."""

    title: str
    design: DesignResult
    simulation: SimulationResult  # the run with the file's own [simulation] settings, with series
    comparison: tuple[ComparisonRow, ...]
    stages: tuple[StageReport, ...]
    accuracy: AccuracyStudy | None  # None with --quick, or when the study failed (``accuracy_failure``)
    warnings: tuple[str, ...] = field(default_factory=tuple)
    rating: tuple[RatingComparison, ...] = ()  # with [rating] (issue 22)
    diagnostics: tuple = field(default_factory=tuple)  # gearcli.diagnostics.Diagnostic of the warnings
    modes: ModalAnalysis | None = None  # at the drive's boundary (None: not computed, e.g. a stand-in simulation)
    campbell: CampbellData | None = None  # for the Campbell figure
    accuracy_failure: str | None = None  # why the accuracy study failed (``accuracy`` is then None)
    theory_point: TheoryPoint | None = None  # the operating point the theory is taken at (None: the nominal one)

    @property
    def natural_frequencies_Hz(self) -> tuple[float, ...]:
        return tuple(self.simulation.natural_frequencies_Hz)

    @property
    def energy_residual(self) -> float:
        return float(self.simulation.solver.energy_residual)
