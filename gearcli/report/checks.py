"""The report's own checks on a simulation, beside the warnings the simulation already gives.

Contact loss and penetration beyond the full-damping depth are the simulation's own warnings
(``gearcli.simulate.stats``, which knows which flank is loaded and when a full-damping depth below
the static approach is deliberate); the report adds what only it can see: the energy balance
against a limit, lines the output sampling cannot resolve, and the accuracy study's verdicts.
The energy check returns plain sentences, the sampling and accuracy checks their warnings with their data;
nothing here prints.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

from gearcli.config.schema import MAX_STEPS
from gearcli.core.jsontypes import JsonValue
from gearcli.diagnostics import ACCURACY, ENERGY_RESIDUAL, SAMPLING, Diagnostic, has, warning
from gearcli.report.accuracy import struggling, struggling_text
from gearcli.report.result import AccuracyStudy, StageReport
from gearcli.simulate.results import SimulationResult

#: |energy residual| above this (relative to the largest energy) is worth a warning
ENERGY_RESIDUAL_LIMIT = 1e-3


def energy_check(sim: SimulationResult, limit: float = ENERGY_RESIDUAL_LIMIT) -> list[str]:
    """|residual| beyond ``limit``, either sign (a negative residual means energy was created), unless
    the simulation already said so."""
    r = sim.solver.energy_residual
    if abs(r) > limit and not has(sim.diagnostics, ENERGY_RESIDUAL):  # by code, never by message text
        return [f"energy balance residual {r:.2e} exceeds ±{limit:.0e} of the largest energy: the integration "
                "is not accurate enough (tighten rtol) or the model books energy it does not account for"]
    return []


#: the Nyquist frequency a suggested ``simulation.steps`` puts above the highest line, as a multiple of it
NYQUIST_MARGIN = 1.25


def _steps_needed(steps: int | None, nyq: float, top_Hz: float) -> int | None:
    """The ``simulation.steps`` that puts the Nyquist frequency (steps / (2 duration): linear in the steps) at
    ``NYQUIST_MARGIN`` times ``top_Hz``; None when the run's steps are not known."""
    if steps is None or steps <= 0:
        return None
    return math.ceil(steps * NYQUIST_MARGIN * top_Hz / nyq)


def _steps_hint(need: int | None) -> str:
    """``--set simulation.steps=N`` (:func:`_steps_needed`); the plain advice when the run's steps are not known or
    N is beyond the schema's maximum."""
    if need is None:
        return "raise simulation.steps"
    if need > MAX_STEPS:
        return (f"raise simulation.steps (it would take {need}, beyond the schema's maximum {MAX_STEPS}: "
                "shorten simulation.duration_s as well)")
    return f"--set simulation.steps={need} would sample it"


def sampling_checks(stages: Sequence[StageReport], natural_Hz: Sequence[float],
                    steps: int | None = None) -> list[Diagnostic]:
    """Lines above the Nyquist frequency of the output sampling alias in the spectrum: a ``sampling`` warning per
    stage whose mesh frequency is above it (its ``stage``) and one for the natural frequencies above it (the train's),
    each with its numbers (docs/output.md, "Warnings"). ``steps``: the run's ``simulation.steps``, for the value that
    would sample them (``steps`` in the data: null when unknown or beyond the schema's maximum)."""
    if not stages or stages[0].spectrum.nyquist_Hz <= 0:
        return []
    nyq = stages[0].spectrum.nyquist_Hz

    def data(top_Hz: float) -> dict[str, JsonValue]:
        need = _steps_needed(steps, nyq, top_Hz)
        return {"nyquist_Hz": nyq, "steps": need if need is not None and need <= MAX_STEPS else None,
                "steps_cap": MAX_STEPS}

    out = [warning(SAMPLING, f"stage {s.stage}: mesh frequency {s.spectrum.mesh_frequency_Hz:.4g} Hz is above the "
                   f"Nyquist frequency {nyq:.4g} Hz of the output samples; "
                   f"{_steps_hint(_steps_needed(steps, nyq, s.spectrum.mesh_frequency_Hz))}",
                   stage=s.stage, excitation=f"stage {s.stage} mesh", frequency_Hz=s.spectrum.mesh_frequency_Hz,
                   **data(s.spectrum.mesh_frequency_Hz))
           for s in stages if s.spectrum.mesh_frequency_Hz > nyq]
    above = [f for f in natural_Hz if f > nyq]
    if above:
        out.append(warning(SAMPLING, f"{len(above)} natural frequenc{'y' if len(above) == 1 else 'ies'} (up to "
                           f"{max(above):.4g} Hz) above the Nyquist frequency {nyq:.4g} Hz of the output samples: they "
                           f"alias in the spectrum; {_steps_hint(_steps_needed(steps, nyq, max(above)))}",
                           stage=None, excitation="natural frequencies", frequency_Hz=max(above),
                           natural_frequencies_Hz=list(above), **data(max(above))))
    return out


def accuracy_checks(study: AccuracyStudy | None, file_method: str, file_rtol: float) -> list[Diagnostic]:
    """The accuracy study's verdicts as ``accuracy`` warnings with their numbers (docs/output.md, "Warnings"): a run
    of the file's settings (or ``auto``) that struggles against the ladder's median, and file settings that miss the
    requested accuracy, with the cheapest rung that meets it."""
    if study is None:
        return []
    out = [warning(ACCURACY, struggling_text(r, median), method=r.method, method_used=r.method_used, rtol=r.rtol,
                   nfev=r.nfev, median_nfev=median)
           for r, median in struggling([r for r in study.runs if r.file_settings or r.method == "auto"], study.runs)]
    if not study.file_settings_meet_accuracy:
        rec = study.recommended
        hint = (f"; the cheapest that does: method = \"{rec.method}\", rtol = {rec.rtol:g}" if rec else "")
        out.append(warning(ACCURACY, f"the file's [simulation] settings (method = \"{file_method}\", rtol = "
                           f"{file_rtol:g}) do not meet the requested accuracy {study.requested_accuracy:g}{hint}",
                           method=file_method, rtol=file_rtol, requested_accuracy=study.requested_accuracy,
                           recommended_method=rec.method if rec else None, recommended_rtol=rec.rtol if rec else None))
    return out
