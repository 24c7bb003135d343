"""A window run the settle loop replaces: its settle test from the window's samples alone, and the brief result the
loop reads from it.

:func:`gearcli.simulate.settle.settled_run` repeats a run whose fixed window is not settled with a later window (or
seeks the periodic state), and reads only the replaced run's ``steady`` and ``window_s``; the run it keeps is
summarised whole (``run_simulation``'s ``unfinished``). A sweep point's settle loop makes ~1.4 such runs (the longer
ones up to 8 times the first's duration), whose statistics, start summary and channels were computed and thrown away.
Here the settle test (:func:`gearcli.simulate.settle.settled_steady`) runs first, on the window's samples only (the
elements' laws are evaluated sample by sample, so the window's forces are the same numbers as the whole run's over
the window); a window found settled goes on to the whole summary with that test's result, an unsettled one returns
:func:`brief_result`: the solver's counters, the energy balance (from the run's first and last samples, the same
numbers), the window's speeds and ratio, the final state and the settle test, without stage statistics, series or
the start summary.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from gearcli import diagnostics as dg
from gearcli.diagnostics import Diagnostic
from gearcli.model import TorsionalModel
from gearcli.model.outputs import Sampled, sample, tooth_forces
from gearcli.simulate import settle as settle_mod
from gearcli.simulate import stats
from gearcli.simulate.choice import Choice
from gearcli.simulate.results import EnergyBalance, SimulationResult, SolverStats, SteadyState
from gearcli.simulate.solver import Integration

RAD_TO_DEG = 180.0 / np.pi


@dataclass(frozen=True)
class _Reference:
    """What the settle test reads of a stage's statistics: the static F_t its factors refer to."""

    simulated_static_tangential_N: float


def applies(model: TorsionalModel, *, replaceable: bool, steady: str, error_estimate: bool, diagnose: bool) -> bool:
    """Whether the run's settle test can come first: a fixed window the settle loop may replace, without the check
    pass (which reads every sample) and without a motor (whose start, read from the whole run, enters the test)."""
    return replaceable and steady != "periodic" and not error_estimate and diagnose \
        and model.layout.drive.motor is None


def window_settle(model: TorsionalModel, run: Integration, choice: Choice, mask_window: tuple[float, float],
                  window: tuple[float, float], steady: SteadyState,
                  simulated_static_N: list[float]) -> tuple[SteadyState, Sampled]:
    """``steady`` with the settle test of the window (:func:`gearcli.simulate.settle.settled_steady`), from the
    window's samples (``mask_window`` selects them, ``window`` is the reported one), and those samples (speeds and
    connector forces); ``simulated_static_N``: per stage, the static F_t of the simulation's load."""
    lay = model.layout
    sel = stats.window_slice(stats.window_mask(np.asarray(run.t, dtype=float), mask_window))
    w = sample(lay, run.t[sel], run.y[:, sel], torques=False)
    forces = [(tooth_forces(lay, k, ms.line_force_N)[0],) for k, ms in enumerate(w.meshes)]
    scratch: list[Diagnostic] = []  # an unsettled window's warning is its whole result's (run_simulation's finish)
    return settle_mod.settled_steady(model, choice, w.time_s, np.ones(w.time_s.size, dtype=bool), window, forces,
                                     [_Reference(float(f)) for f in simulated_static_N], steady, None, scratch), w


def brief_result(model: TorsionalModel, run: Integration, choice: Choice, window: tuple[float, float],
                 window_samples: Sampled, steady: SteadyState, diags: list[Diagnostic],
                 solver: SolverStats) -> SimulationResult:
    """The replaced run's result: ``steady`` (unsettled) and the window, the solver's counters with the energy
    residual, the window's mean speeds and ratio (from ``window_samples``, :func:`window_settle`'s), the final state;
    no stage statistics nor series (the settle loop reads none; the run it keeps is summarised whole)."""
    lay = model.layout
    ends = [0, run.t.size - 1]
    energy = model.energy(sample(lay, run.t[ends], run.y[:, ends], torques=False), run.y)
    shafts = window_samples.shaft_omega_rad_s
    w_in, w_out = float(shafts[0].mean()), float(shafts[-1].mean())
    ratio, _ = stats.ratio_of(w_in, w_out)
    balance = EnergyBalance(energy.input_work_J, energy.load_work_J, energy.damping_loss_J, energy.kinetic_change_J,
                            energy.potential_change_J, energy.residual_relative)
    return SimulationResult(
        time_s=np.empty(0), series={}, window_s=(float(window[0]), float(window[1])), ratio=ratio,
        output_speed_deg_s=w_out * RAD_TO_DEG, input_speed_deg_s=w_in * RAD_TO_DEG, stages=(),
        solver=replace(solver, energy_residual=energy.residual_relative), energy=balance,
        warnings=dg.messages(diags), diagnostics=tuple(diags),
        natural_frequencies_Hz=choice.natural_frequencies_Hz, natural_frequencies_boundary=choice.boundary,
        final_state=run.y[:, -1].copy(), final_time_s=float(run.t[-1]), steady=steady,
        extra={"parametric_work_J": energy.parametric_work_J, "stiffness_indicator": choice.indicator})
