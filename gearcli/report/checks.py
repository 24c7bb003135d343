"""The report's own checks on a simulation, beside the warnings the simulation already gives.

Contact loss and penetration beyond the full-damping depth are the simulation's own warnings
(``gearcli.simulate.stats``, which knows which flank is loaded and when a full-damping depth below
the static approach is deliberate); the report adds what only it can see: the energy balance
against a limit, lines the output sampling cannot resolve, and the accuracy study's verdicts.
Each check returns plain sentences; nothing here prints.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

from gearcli.config.schema import MAX_STEPS
from gearcli.diagnostics import ENERGY_RESIDUAL, has
from gearcli.report.accuracy import struggling_runs
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


def _steps_hint(steps: int | None, nyq: float, top_Hz: float) -> str:
    """``--set simulation.steps=N`` that puts the Nyquist frequency (steps / (2 duration): linear in the steps) at
    ``NYQUIST_MARGIN`` times ``top_Hz``; the plain advice when the run's steps are not known or N is beyond the
    schema's maximum."""
    if steps is None or steps <= 0:
        return "raise simulation.steps"
    need = math.ceil(steps * NYQUIST_MARGIN * top_Hz / nyq)
    if need > MAX_STEPS:
        return (f"raise simulation.steps (it would take {need}, beyond the schema's maximum {MAX_STEPS}: "
                "shorten simulation.duration_s as well)")
    return f"--set simulation.steps={need} would sample it"


def sampling_checks(stages: Sequence[StageReport], natural_Hz: Sequence[float], steps: int | None = None) -> list[str]:
    """Lines above the Nyquist frequency of the output sampling alias in the spectrum. ``steps``: the run's
    ``simulation.steps``, for the value that would sample them."""
    if not stages or stages[0].spectrum.nyquist_Hz <= 0:
        return []
    nyq = stages[0].spectrum.nyquist_Hz
    out = [f"stage {s.stage}: mesh frequency {s.spectrum.mesh_frequency_Hz:.4g} Hz is above the Nyquist frequency "
           f"{nyq:.4g} Hz of the output samples; {_steps_hint(steps, nyq, s.spectrum.mesh_frequency_Hz)}"
           for s in stages if s.spectrum.mesh_frequency_Hz > nyq]
    above = [f for f in natural_Hz if f > nyq]
    if above:
        out.append(f"{len(above)} natural frequenc{'y' if len(above) == 1 else 'ies'} (up to {max(above):.4g} Hz) "
                   f"above the Nyquist frequency {nyq:.4g} Hz of the output samples: they alias in the "
                   f"spectrum; {_steps_hint(steps, nyq, max(above))}")
    return out


def accuracy_checks(study: AccuracyStudy | None, file_method: str, file_rtol: float) -> list[str]:
    if study is None:
        return []
    out = struggling_runs([r for r in study.runs if r.file_settings or r.method == "auto"], study.runs)
    if not study.file_settings_meet_accuracy:
        rec = study.recommended
        hint = (f"; the cheapest that does: method = \"{rec.method}\", rtol = {rec.rtol:g}" if rec else "")
        out.append(f"the file's [simulation] settings (method = \"{file_method}\", rtol = {file_rtol:g}) do not "
                   f"meet the requested accuracy {study.requested_accuracy:g}{hint}")
    return out
