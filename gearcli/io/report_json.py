"""``gearcli report --format json``: the report as a plain dict (strict JSON via ``serialize.to_json``).

Keys: ``comparison`` [{stage, quantity, theory, simulated, error_percent}] (stage null: the train),
``dynamics`` (per stage: force statistics, run-up peak, spectrum peak), ``accuracy`` (null with
--quick or when the study failed) {requested_accuracy, reference, runs, recommended, file_settings_meet_accuracy,
notes}, ``accuracy_failure`` (why the study failed, else null), ``design`` and ``simulation`` summaries, ``energy_residual``, ``warnings``. Errors in ``runs`` are
relative (not %); an error below the reference's uncertainty keeps its number and is flagged in
``below_reference_resolution``.
"""

from __future__ import annotations

import dataclasses
import math

from gearcli.core.jsontypes import JsonObject, JsonValue
from gearcli.diagnostics import warning_objects
from gearcli.io.modes_out import modes_dict
from gearcli.io.serialize import as_object, plain, simulation_dict
from gearcli.io.units import OutputUnits, of_result
from gearcli.report.result import AccuracyRun, AccuracyStudy, Report, StageReport
from gearcli.results import DesignResult

DESIGN_STAGE_KEYS = ("index", "ratio", "mesh_frequency_Hz", "contact_ratio_transverse", "overlap_ratio",
                     "contact_ratio_total", "hertz_stiffness_N_mm1_5", "linearised_stiffness_N_mm",
                     "static_approach_mm", "static_force_N",
                     # what the design section of the markdown and table prints, under `design`'s own key names
                     "normal_module_mm", "helix_angle_deg", "center_distance_mm", "face_width_mm",
                     "iso6336_mesh_stiffness_N_mm_um")


def _stage_summary(s) -> JsonObject:
    out: JsonObject = {k: plain(getattr(s, k)) for k in DESIGN_STAGE_KEYS}
    # the contact law the run integrates ({law, K, exponent, linearised_N_mm, iso_N_mm, ...}, as `design` gives it):
    # hertz_stiffness_N_mm1_5 is the Hertz line contact's K, not the default iso6336 law's
    out["mesh_stiffness"] = plain(getattr(s, "mesh_stiffness", None))
    out["pinion"] = {"teeth": s.pinion.teeth}
    out["gear"] = {"teeth": s.gear.teeth}
    return out


def design_summary(d: DesignResult) -> JsonObject:
    return {
        "title": d.title,
        "total_ratio": d.total_ratio,
        "input_speed_deg_s": d.input_speed_deg_s,
        "output_speed_deg_s": d.output_speed_deg_s,
        "output_speed_rpm": d.output_speed_rpm,
        "input_torque_Nmm": d.input_torque_Nmm,
        "output_torque_Nmm": d.output_torque_Nmm,
        "stages": [_stage_summary(s) for s in d.stages],
        "shaft_speeds_deg_s": [sh.speed_deg_s for sh in d.shafts],
        **_in_file_units(d),
        "warnings": warning_objects(d.warnings, d.diagnostics),
    }


def _in_file_units(d: DesignResult) -> JsonObject:
    """Beside the fixed °/s and N·mm keys, the design file's own units (docs/output.md, "Units"): ``units``, a
    speed key other than °/s as ``input_speed_<u>``, ``output_speed_<u>``, ``shaft_speeds_<u>``, N·m torques."""
    if d.units is None:
        return {}
    u = OutputUnits(*d.units)
    out: JsonObject = {"units": {"speed": u.speed, "torque": u.torque}}
    if u.speed != "deg_s":
        out[f"input_speed_{u.speed}"] = u.speed_from_deg_s(d.input_speed_deg_s)
        out[f"output_speed_{u.speed}"] = u.speed_from_deg_s(d.output_speed_deg_s)
        out[f"shaft_speeds_{u.speed}"] = [u.speed_from_deg_s(sh.speed_deg_s) for sh in d.shafts]
    if u.torque == "Nm":
        out["input_torque_Nm"] = d.input_torque_Nmm / 1000.0
        out["output_torque_Nm"] = d.output_torque_Nmm / 1000.0
    return out


def stage_dict(s: StageReport) -> JsonObject:
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
        "runup_factor": s.runup_factor,
        "simulated_static_tangential_N": s.simulated_static_tangential_N,
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


def run_dict(r: AccuracyRun | None) -> JsonObject | None:
    return None if r is None else as_object(plain(dataclasses.asdict(r)))


def accuracy_dict(study: AccuracyStudy | None) -> JsonObject | None:
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


def _finite(doc: JsonValue) -> JsonValue:
    """``doc`` with every non-finite float as None (JSON null): JSON has no infinity or NaN, and a degenerate
    window (a handful of samples) may leave a derived figure undefined."""
    if isinstance(doc, dict):
        return {k: _finite(v) for k, v in doc.items()}
    if isinstance(doc, (list, tuple)):
        return [_finite(v) for v in doc]
    if isinstance(doc, float) and not math.isfinite(doc):
        return None
    return doc


def report_dict(r: Report) -> JsonObject:
    doc = _finite(_report_dict(r))
    assert isinstance(doc, dict)
    return doc


def _report_dict(r: Report) -> JsonObject:
    sim = simulation_dict(r.simulation, series=False)
    sim.pop("warnings", None)  # merged into the report's own list
    return {  # the engineering first, the numerical study after it
        "title": r.title,
        "design": design_summary(r.design),
        "modes": modes_summary(r),
        "comparison": comparison_rows(r),
        # where the theory is taken when the drive does not prescribe the speed (null: the design's nominal point)
        "theory_point": None if r.theory_point is None else {**plain(r.theory_point),  # type: ignore[dict-item]
                                                             "speed_factor": r.theory_point.speed_factor},
        "dynamics": [stage_dict(s) for s in r.stages],
        "natural_frequencies_Hz": list(r.natural_frequencies_Hz),
        **({"rating": [plain(c) for c in r.rating]} if r.rating else {}),  # ISO against simulated K_v (issue 22)
        "simulation": sim,
        "energy_residual": r.energy_residual,
        "accuracy": accuracy_dict(r.accuracy),
        "accuracy_failure": r.accuracy_failure,  # why the study failed (accuracy null); null otherwise
        "warnings": warning_objects(r.warnings, r.diagnostics),
    }


def comparison_rows(r: Report) -> list[JsonValue]:
    """The theory-against-simulation rows; in a file whose speed key is not °/s, the speed rows (kept in °/s under
    their fixed names, in their places) again in the file's unit after them all (``input_speed_rpm``, ...: DESIGN
    §12), so a script that reads the rows by position finds the same rows where they were."""
    u = of_result(r.simulation)
    rows: list[JsonValue] = [plain(row) for row in r.comparison]
    if u.speed != "deg_s":
        rows += [plain(dataclasses.replace(row, quantity=row.quantity[: -len("deg_s")] + u.speed,
                                           theory=u.speed_from_deg_s(row.theory),
                                           simulated=u.speed_from_deg_s(row.simulated)))
                 for row in r.comparison if row.quantity.endswith("_speed_deg_s")]
    return rows


def modes_summary(r: Report) -> JsonObject | None:
    """The modes at the drive's boundary (as ``gearcli modes``), null where the report did not compute them."""
    if r.modes is None:
        return None

    doc = modes_dict([r.modes])
    doc.pop("warnings", None)
    return {"boundary": r.modes.boundary, **{k: v for k, v in doc.items() if k != "boundaries"},
            "modes": as_object(doc["boundaries"])[r.modes.boundary]}
