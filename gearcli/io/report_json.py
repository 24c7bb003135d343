"""``gearcli report --format json``: the report as a plain dict (strict JSON via ``serialize.to_json``).

Keys: ``comparison`` [{stage, quantity, theory, simulated, error_percent}] (stage null: the train),
``dynamics`` (per stage: force statistics, run-up peak, spectrum peak), ``accuracy`` (null with
--quick) {requested_accuracy, reference, runs, recommended, file_settings_meet_accuracy, notes},
``design`` and ``simulation`` summaries, ``energy_residual``, ``warnings``. Errors in ``runs`` are
relative (not %); an error below the reference's uncertainty keeps its number and is flagged in
``below_reference_resolution``.
"""

from __future__ import annotations

import dataclasses

from gearcli.io.serialize import plain, simulation_dict
from gearcli.report.result import AccuracyRun, AccuracyStudy, Report, StageReport
from gearcli.results import DesignResult

DESIGN_STAGE_KEYS = ("index", "ratio", "mesh_frequency_Hz", "contact_ratio_transverse", "overlap_ratio",
                     "contact_ratio_total", "hertz_stiffness_N_mm1_5", "linearised_stiffness_N_mm",
                     "static_approach_mm", "static_force_N")


def design_summary(d: DesignResult) -> dict:
    return {
        "title": d.title,
        "total_ratio": d.total_ratio,
        "input_speed_deg_s": d.input_speed_deg_s,
        "output_speed_deg_s": d.output_speed_deg_s,
        "output_speed_rpm": d.output_speed_rpm,
        "input_torque_Nmm": d.input_torque_Nmm,
        "output_torque_Nmm": d.output_torque_Nmm,
        "stages": [{k: plain(getattr(s, k)) for k in DESIGN_STAGE_KEYS} for s in d.stages],
        "shaft_speeds_deg_s": [sh.speed_deg_s for sh in d.shafts],
        "warnings": list(d.warnings),
    }


def stage_dict(s: StageReport) -> dict:
    sp = s.spectrum
    return {
        "stage": s.stage,
        "tangential_N": plain(s.tangential_N),
        "radial_N": plain(s.radial_N),
        "axial_N": plain(s.axial_N),
        "static_tangential_N": s.static_tangential_N,
        "peak_tangential_N": s.peak_tangential_N,
        "peak_time_s": s.peak_time_s,
        "dynamic_factor": s.dynamic_factor,
        "spectrum": {
            "peak_frequency_Hz": sp.peak_frequency_Hz,
            "peak_amplitude_N": sp.peak_amplitude_N,
            "resolution_Hz": sp.resolution_Hz,
            "nyquist_Hz": sp.nyquist_Hz,
            "window_s": list(sp.window_s),
            "mesh_frequency_Hz": sp.mesh_frequency_Hz,
            "matches": sp.matches,
            "mesh_orders": [plain(o) for o in sp.mesh_orders],
        },
    }


def run_dict(r: AccuracyRun | None) -> dict | None:
    return None if r is None else plain(dataclasses.asdict(r))


def accuracy_dict(study: AccuracyStudy | None) -> dict | None:
    if study is None:
        return None
    ref = dataclasses.asdict(study.reference)
    ref.pop("metrics")
    ref["values"] = plain(study.reference.metrics)
    return {
        "requested_accuracy": study.requested_accuracy,
        "reference": ref,
        "runs": [run_dict(r) for r in study.runs],
        "recommended": run_dict(study.recommended),
        "file_settings_meet_accuracy": study.file_settings_meet_accuracy,
        "notes": list(study.notes),
    }


def report_dict(r: Report) -> dict:
    sim = simulation_dict(r.simulation, series=False)
    sim.pop("warnings", None)  # merged into the report's own list
    return {
        "title": r.title,
        "comparison": [plain(row) for row in r.comparison],
        "dynamics": [stage_dict(s) for s in r.stages],
        "natural_frequencies_Hz": list(r.natural_frequencies_Hz),
        "accuracy": accuracy_dict(r.accuracy),
        "energy_residual": r.energy_residual,
        "design": design_summary(r.design),
        **({"rating": [plain(c) for c in r.rating]} if r.rating else {}),  # ISO against simulated K_v (issue 22)
        "simulation": sim,
        "warnings": list(r.warnings),
    }
