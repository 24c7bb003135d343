"""``run_simulation``: the design file's scene, integrated and summarised into a SimulationResult."""

from __future__ import annotations

import math
from typing import Optional

import numpy as np

from gearcli.errors import SimulationError
from gearcli.model import TorsionalModel, spec_from_design
from gearcli.model.outputs import Sampled, sample, tooth_forces
from gearcli.results import EnergyBalance, SimulationResult, SolverStats
from gearcli.simulate import stats
from gearcli.simulate.choice import EXPLICIT, IMPLICIT_METHOD, STIFFNESS_LIMIT, Choice, choose_method
from gearcli.simulate.guards import force_noise_warnings, nfev_budget, require_feasible
from gearcli.simulate.solver import (STATUS_BUDGET, STATUS_ENERGY, STATUS_FAILED, STATUS_FINISHED, STATUS_NONFINITE,
                                     Integration, integrate)

RAD_TO_DEG = 180.0 / math.pi


def run_simulation(cfg, design, *, method: Optional[str] = None, rtol: Optional[float] = None,
                   want_series: bool = True, max_nfev: Optional[int] = None,
                   y0: Optional[np.ndarray] = None) -> SimulationResult:
    """Simulate a validated ``DesignFile`` with its ``DesignResult`` (``method``/``rtol`` default to
    ``cfg.simulation``). ``want_series=False`` leaves ``time_s`` and ``channels`` empty (the statistics
    are still computed from the full samples). ``max_nfev`` defaults to the scene's budget
    (:func:`gearcli.simulate.guards.nfev_budget`). ``y0`` overrides the initial state (continuation;
    ``SimulationResult.final_state`` of a previous run). Raises SimulationError on failure, never returns NaN."""
    sim = cfg.simulation
    return simulate_model(TorsionalModel(spec_from_design(cfg, design)), duration_s=sim.duration_s,
                          steps=sim.steps, method=method or sim.method, rtol=rtol or sim.rtol,
                          window_start_s=sim.window_start_s, want_series=want_series, max_nfev=max_nfev,
                          y0=y0)


def simulate_model(model: TorsionalModel, *, duration_s: float, steps: int, method: str = "auto",
                   rtol: float = 1e-6, window_start_s: Optional[float] = None, want_series: bool = True,
                   y0: Optional[np.ndarray] = None, max_nfev: Optional[int] = None) -> SimulationResult:
    """The engine of :func:`run_simulation` on an assembled model (also used by tests with plain
    parameters); ``y0`` overrides the initial state (layout: :mod:`gearcli.model.layout`)."""
    spec = model.spec
    window, warnings = stats.steady_window(spec, duration_s, window_start_s)
    choice = choose_method(spec, duration_s, method)
    if max_nfev is None:  # the scene's own budget; an explicit method that cannot meet it is refused now
        max_nfev = nfev_budget(choice.indicator, rtol)
        require_feasible(choice, max_nfev)
    t_eval = np.linspace(0.0, duration_s, steps + 1)
    run = integrate(model, t_eval, choice.method, rtol, y0=y0, max_nfev=max_nfev)
    check(run, choice, duration_s)
    s = sample(model.layout, run.t, run.y)
    energy = model.energy(s, run.y)
    warnings += stats.model_warnings(spec) + _choice_warnings(choice) + force_noise_warnings(choice, rtol)
    result = _summarise(model, s, run, choice, window, energy, warnings, want_series)
    _require_finite(result)
    return result


def _channels(model: TorsionalModel, s: Sampled) -> tuple[dict[str, np.ndarray], list[tuple]]:
    """DESIGN.md section 5 columns, in order; and per stage (F_t, F_r, F_a, penetration mm)."""
    ch: dict[str, np.ndarray] = {f"shaft{i + 1}_speed_deg_s": s.omega_rad_s[i] * RAD_TO_DEG
                                 for i in range(model.layout.n_shafts)}
    ch["input_torque_Nmm"] = s.input_torque_Nm * 1e3
    per_stage = []
    for k, ms in enumerate(s.meshes):
        ft, fr, fa = tooth_forces(model.layout, k, ms.line_force_N)
        pen = ms.penetration_m * 1e3
        ch.update({f"stage{k + 1}_tangential_N": ft, f"stage{k + 1}_radial_N": fr,
                   f"stage{k + 1}_axial_N": fa, f"stage{k + 1}_penetration_mm": pen})
        per_stage.append((ft, fr, fa, pen))
    return ch, per_stage


def _summarise(model: TorsionalModel, s: Sampled, run: Integration, choice: Choice, window, energy,
               warnings: list[str], want_series: bool) -> SimulationResult:
    spec = model.spec
    mask = stats.window_mask(s.time_s, window)
    channels, per_stage = _channels(model, s)
    stages = tuple(stats.stage_dynamics(k, s.time_s, mask, *per_stage[k], m.static_tangential_N)
                   for k, m in enumerate(spec.meshes))
    w_in, w_out = float(s.omega_rad_s[0][mask].mean()), float(s.omega_rad_s[-1][mask].mean())
    ratio, ratio_warnings = stats.ratio_of(w_in, w_out)
    warnings += ratio_warnings + stats.contact_warnings(spec, mask, [ms.penetration_m for ms in s.meshes],
                                                        choice.at_full_load.penetration_m)
    warnings += stats.peak_warnings(spec, [float(np.max(np.abs(ms.line_force_N))) for ms in s.meshes],
                                    choice.at_operating_point.line_forces_N)
    if energy.residual_relative > stats.WARN_ENERGY_RESIDUAL:
        warnings.append(f"energy balance residual {energy.residual_relative:.2g} exceeds "
                        f"{stats.WARN_ENERGY_RESIDUAL:g}: tighten simulation.rtol")
    solver = SolverStats(
        method=run.method, requested_method=choice.requested, choice_reason=choice.reason, rtol=run.rtol,
        atol=_atol_summary(model, run.atol),
        nfev=run.nfev, njev=run.njev, nlu=run.nlu, steps=run.steps, wall_s=run.wall_s,
        energy_residual=energy.residual_relative, status=run.status, message=run.message)
    balance = EnergyBalance(energy.input_work_J, energy.load_work_J, energy.damping_loss_J, energy.kinetic_change_J,
                            energy.potential_change_J, energy.residual_relative)
    return SimulationResult(
        time_s=s.time_s if want_series else np.empty(0), channels=channels if want_series else {},
        window_s=(float(window[0]), float(window[1])), ratio=ratio, output_speed_deg_s=w_out * RAD_TO_DEG,
        input_speed_deg_s=w_in * RAD_TO_DEG, stages=stages, solver=solver, energy=balance,
        warnings=tuple(warnings),
        natural_frequencies_Hz=choice.natural_frequencies_Hz, final_state=np.array(run.y[:, -1]),
        extra={"parametric_work_J": energy.parametric_work_J,
               "stiffness_indicator": choice.indicator,
               "natural_frequencies_runup_Hz": [float(f) for f in choice.at_operating_point.natural_frequencies_Hz]},
    )


def _atol_summary(model: TorsionalModel, atol: np.ndarray) -> dict[str, float]:
    """The smallest absolute tolerance of each state group (deflections, speeds)."""
    m, lay = model.layout.n_meshes, model.layout
    return {"deflection_m": float(atol[:m].min()),
            "speed_rad_s": float(atol[m:m + len(lay.free_shafts)].min())}


def _choice_warnings(choice: Choice) -> list[str]:
    if choice.method in EXPLICIT and choice.indicator > STIFFNESS_LIMIT:
        return [f"the scene is stiff for an explicit method (max|λ|·T = {choice.indicator:.2g}, at least "
                f"{choice.explicit_evaluations(choice.method):.2g} evaluations for stability alone): "
                f'method = "auto" would use {IMPLICIT_METHOD}']
    return []


def check(run: Integration, choice: Choice, duration_s: float) -> None:
    """Raise SimulationError naming the likely cause and the fix when the run did not finish."""
    if run.status == STATUS_FINISHED:
        if not np.all(np.isfinite(run.y)):
            raise SimulationError(f"{run.method} returned non-finite values; {_stiffness_hint(choice)}")
        return
    where = f"{run.method} stopped at t = {run.t_fail:.4g} s of {duration_s:g} s"
    if run.status == STATUS_BUDGET:
        if run.method in EXPLICIT:
            raise SimulationError(f"{where}: {run.message}. {_stiffness_hint(choice)}")
        raise SimulationError(f"{where}: {run.message}; the run is too long for its dynamics or the contacts "
                              "impact violently — shorten simulation.duration_s or loosen simulation.rtol")
    if run.status in (STATUS_NONFINITE, STATUS_ENERGY):
        cause = "the solution diverged (non-finite state)" if run.status == STATUS_NONFINITE \
            else "the solution is unstable"
        raise SimulationError(f"{where}: {cause}: {run.message}. {_divergence_hint(choice, run)}")
    if run.status == STATUS_FAILED:
        raise SimulationError(f"{where}: the step size collapsed (solver: {run.message}); likely a violent contact "
                              "impact or a discontinuous stiffness — try method = \"Radau\" or a looser rtol")
    raise SimulationError(f"{where}: {run.message}")


def _divergence_hint(choice: Choice, run: Integration) -> str:
    """The fix for a diverging run: an implicit method for a stiff scene, else a tighter tolerance."""
    if run.method in EXPLICIT:
        return _stiffness_hint(choice)
    return (f"tighten simulation.rtol (now {run.rtol:g}, try {run.rtol / 100:g}); if it persists, check the contact "
            f"law of mesh stage {choice.stiffest_mesh + 1} (stiffness, exponent) and the inertias")


def _stiffness_hint(choice: Choice) -> str:
    k = choice.stiffest_mesh
    freqs = choice.at_operating_point.natural_frequencies_Hz
    f = float(freqs[-1]) if freqs.size else 0.0
    if choice.method in EXPLICIT and choice.indicator > STIFFNESS_LIMIT:
        return (f"mesh stage {k + 1} makes the scene stiff (highest mode {f:.3g} Hz, "
                f"max|λ|·T = {choice.indicator:.3g}, {choice.indicator / STIFFNESS_LIMIT:.2g}x what an explicit "
                "method affords here): "
                f'use method = "{IMPLICIT_METHOD}" (or "auto")')
    return (f"check the contact law of mesh stage {k + 1} (stiffness, exponent) and the inertias; "
            f'try method = "{IMPLICIT_METHOD}" with a tighter rtol')


def _require_finite(result: SimulationResult) -> None:
    bad = [name for name, x in result.channels.items() if not np.all(np.isfinite(x))]
    scalars = [result.ratio, result.output_speed_deg_s, result.energy.residual_relative]
    if bad or not all(math.isfinite(v) for v in scalars):
        raise SimulationError("the simulation produced non-finite values"
                              + (f" in {', '.join(bad[:4])}" if bad else "") + "; this is a bug, please report it")
