"""Result objects to plain dicts and CSV text: the machine-readable contract of docs/output.md."""

from __future__ import annotations

import csv
import dataclasses
import io
import json
import math
from collections.abc import Iterable, Sequence
from typing import Any, Protocol, TypeAlias, cast

import numpy as np

import gearcli
from gearcli.core.jsontypes import JsonObject, JsonScalar, JsonValue
from gearcli.core.text import csv_text_cell
from gearcli.diagnostics import warning_objects
from gearcli.io import units as output_units
from gearcli.io.channels import named
from gearcli.io.units import channels, of_result
from gearcli.results import DesignResult, drop_absent_bearing_keys
from gearcli.simulate.results import SimulationResult
from gearcli.stages import kinds

#: a JSON object while this module rearranges it (nested keys moved, popped); the public functions return
#: :data:`~gearcli.core.jsontypes.JsonObject`
_Doc: TypeAlias = dict[str, Any]


def plain(obj: object) -> JsonValue:
    """Dataclasses, tuples and numpy scalars/arrays to JSON-ready Python values."""
    return _plain(obj)


def _plain(obj: object) -> Any:
    if dataclasses.is_dataclass(obj) and not isinstance(obj, type):
        return {f.name: _plain(getattr(obj, f.name)) for f in dataclasses.fields(obj)}
    if isinstance(obj, dict):
        return {str(k): _plain(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_plain(v) for v in obj]
    if hasattr(obj, "tolist"):  # numpy array or scalar
        return _plain(obj.tolist())
    if isinstance(obj, float) and obj == 0.0:
        return 0.0  # no negative zero in the output (a held member's speed, a carrier-held stage's)
    return obj  # a JSON scalar: str, int, float, bool or None


def as_object(value: JsonValue) -> JsonObject:
    """``value`` as a JSON object (a TypeError when it is not one)."""
    if not isinstance(value, dict):
        raise TypeError(f"expected a JSON object, got {type(value).__name__}")
    return value


def with_meta(payload: JsonObject, sha256: str) -> JsonObject:
    """Every JSON document carries the tool version and the hash of its input."""
    return {"gearcli_version": gearcli.__version__, "input_sha256": sha256, **payload}


def design_dict(result: DesignResult) -> JsonObject:
    return _design_doc(result)


def _design_doc(result: DesignResult) -> _Doc:
    doc: _Doc = _plain(dataclasses.replace(result, diagnostics=(), units=None))
    doc.pop("diagnostics", None)
    doc.pop("units", None)
    if not result.bearings:  # a design file without [[bearing]] tables means what it meant before them
        doc.pop("bearings", None)
    for b in doc.get("bearings", []):  # planet_stage: a planet pin's bearings only
        if b.get("planet_stage") is None:
            b.pop("planet_stage", None)
        drop_absent_bearing_keys(b)
    for s in doc["stages"]:
        _drop_absent_allowances(s)
    doc["stages"] = [_stage_json(s) for s in doc["stages"]]
    doc["warnings"] = warning_objects(result.warnings, result.diagnostics)
    return _in_file_units(doc, result) if result.units is not None else doc


def _in_file_units(doc: _Doc, result: DesignResult) -> _Doc:
    """The contract's fixed keys (°/s and rpm, N·mm and N·m per member) and, besides them, the design file's own
    units where those are not among them: ``units`` {speed, torque}; a ``speed_rad_s`` file's ``input_speed_rad_s``,
    ``output_speed_rad_s`` and every member's and shaft's ``speed_rad_s``; a ``torque_Nm`` (or ``power_kW``) file's
    ``input_torque_Nm``, ``output_torque_Nm`` (docs/output.md, "Units")."""
    assert result.units is not None
    u = output_units.OutputUnits(*result.units)
    out: _Doc = {}
    for key, value in doc.items():
        out[key] = value
        if key == "output_speed_rpm" and u.speed == "rad_s":
            out["input_speed_rad_s"] = u.speed_from_deg_s(result.input_speed_deg_s)
            out["output_speed_rad_s"] = u.speed_from_deg_s(result.output_speed_deg_s)
        elif key == "output_torque_Nmm" and u.torque == "Nm":
            out["input_torque_Nm"] = result.input_torque_Nmm / 1000.0
            out["output_torque_Nm"] = result.output_torque_Nmm / 1000.0
    out["units"] = {"speed": u.speed, "torque": u.torque}
    if u.speed == "rad_s":
        _add_rad_s(out, u)
    return out


def _add_rad_s(node: JsonValue, u: output_units.OutputUnits) -> None:
    """``speed_rad_s`` after ``speed_rpm`` in every object that has ``speed_deg_s`` (members, shafts), in place."""
    if isinstance(node, list):
        for v in node:
            _add_rad_s(v, u)
    elif isinstance(node, dict):
        for v in node.values():
            _add_rad_s(v, u)
        deg = node.get("speed_deg_s")
        if isinstance(deg, (int, float)) and "speed_rpm" in node:
            items = list(node.items())
            node.clear()
            for k, v in items:
                node[k] = v
                if k == "speed_rpm":
                    node["speed_rad_s"] = u.speed_from_deg_s(float(deg))


# the allowances' figures and the CSV column suffixes of their limits (docs/output.md); absent without the keys
ALLOWANCE_LIMITS = {"generating_profile_shift": ("e", "i"), "manufactured_root_diameter_mm": ("e", "i"),
                    "backlash_circumferential_mm": ("max", "min"), "backlash_normal_mm": ("max", "min"),
                    "contact_ratio_transverse_with_allowances": ("e", "m", "i")}


def _drop_absent_allowances(d: _Doc) -> None:
    """A design without allowance keys keeps today's JSON: its (None) allowance figures are left out."""
    for key in ALLOWANCE_LIMITS:
        if key in d and d[key] is None:
            del d[key]
    for v in d.values():
        if isinstance(v, dict):
            _drop_absent_allowances(v)


def _allowance_columns(d: _Doc) -> _Doc:
    """The allowances' [upper, lower] lists as named CSV columns (``pinion_generating_profile_shift_e``)."""
    out: _Doc = {}
    for k, v in d.items():
        if k in ALLOWANCE_LIMITS and isinstance(v, list):
            out[k] = dict(zip(ALLOWANCE_LIMITS[k], v, strict=True))
        else:
            out[k] = _allowance_columns(v) if isinstance(v, dict) else v
    return out


class _StageJson(Protocol):
    """What the JSON asks of a stage's kind (:mod:`gearcli.stages.io`)."""

    def json_stage(self, stage: _Doc) -> _Doc:
        """The stage's JSON object from its result's plain dict (which has the kind's ``type``)."""

    def json_simulated_stage(self, stage: JsonObject) -> JsonObject:
        """A simulated stage's JSON object from today's statistics keys (a gear stage's as they are)."""


def _stage_output(stage: object) -> _StageJson:
    return cast(_StageJson, kinds.facet(kinds.kind_of(stage), "io"))


def _stage_json(stage: _Doc) -> _Doc:
    return cast(_StageJson, kinds.facet(str(stage.get("type") or kinds.PARALLEL), "io")).json_stage(stage)


def simulation_dict(result: SimulationResult, *, series: bool = False) -> JsonObject:
    stages = [
        {k: plain(getattr(s, k)) for k in ("index", "tangential_N", "radial_N", "axial_N", "penetration_mm",
                                              "static_tangential_N", "peak_tangential_N", "peak_time_s",
                                              "dynamic_factor", "runup_factor", "simulated_static_tangential_N",
                                              "dte_um", "contact_loss_fraction",
                                              "back_flank_fraction", "regime", "mesh_stiffness", "error_estimate",
                                              "sampling_error")}
        | ({"rating": _stage_rating(s.rating, sharing=bool(s.planets))} if s.rating is not None else {})
        | ({"planet_ring_rating": plain(s.planet_ring_rating)} if s.planet_ring_rating is not None else {})
        | ({"planet_ring_mesh_stiffness": plain(s.planet_ring_mesh_stiffness)}
           if s.planet_ring_mesh_stiffness is not None else {})
        | ({"planets": plain(s.planets), "load_sharing_factor": s.load_sharing_factor} if s.planets else {})
        for s in result.stages
    ]
    stages = [_stage_output(s).json_simulated_stage(doc) for s, doc in zip(result.stages, stages, strict=True)]

    u = output_units.of_result(result)
    speeds = {} if u.speed == "deg_s" else {f"input_speed_{u.speed}": u.speed_from_deg_s(result.input_speed_deg_s),
                                            f"output_speed_{u.speed}": u.speed_from_deg_s(result.output_speed_deg_s)}
    means = output_units.input_torque_window_means(result)
    torque = {} if means is None else {f"input_torque_{u.torque}": u.torque_from_Nm(means[0]),
                                       "input_power_kW": means[1]}
    summary: JsonObject = {
        "ratio": result.ratio,
        "input_speed_deg_s": result.input_speed_deg_s,
        "output_speed_deg_s": result.output_speed_deg_s,
        **speeds,
        **torque,
        "units": {"speed": u.speed, "torque": u.torque},
        "window_s": list(result.window_s),
        "stages": stages,
        "natural_frequencies_Hz": list(result.natural_frequencies_Hz),
        "natural_frequencies_boundary": result.natural_frequencies_boundary,
        "steady": plain(result.steady),
        **_motor_keys((result.extra or {}).get("motor")),
        **({"start": plain((result.extra or {})["start"])} if "start" in (result.extra or {}) else {}),
    }
    out: JsonObject = {
        "summary": summary,
        "solver": plain(result.solver),
        "energy": plain(result.energy),
        "warnings": warning_objects(result.warnings, result.diagnostics),
    }
    if result.extra and "bearings" in result.extra:  # only scenes with [[bearing]] tables (docs/life.md)
        summary["bearings"] = plain(result.extra["bearings"])
    if series:
        shown = output_units.channels(named(result), u)
        out["series"] = {"time_s": result.time_s.tolist(), **{k: v.tolist() for k, v in shown.items()}}
    return out


def _stage_rating(rating: object, *, sharing: bool) -> JsonValue:
    """A simulated stage's rating; K_gamma only where planets share the load (a parallel stage keeps today's keys)."""
    doc = plain(rating)
    if not sharing and isinstance(doc, dict):
        doc.pop("K_gamma", None)
    return doc


def _motor_keys(motor: dict[str, float | None] | None) -> JsonObject:
    """A motor run's summary keys: ``start_time_s`` and ``operating_slip`` beside the other keys, the rest in
    ``motor`` (docs/output.md)."""
    if motor is None:
        return {}
    rest = {k: v for k, v in motor.items() if k not in ("start_time_s", "operating_slip")}
    top = {k: motor[k] for k in ("start_time_s", "operating_slip") if k in motor}
    return {**as_object(plain(top)), "motor": plain(rest)}


def to_json(doc: JsonObject) -> str:
    """Strict JSON: a NaN or infinity in a result is a bug, not an output (``allow_nan=False``)."""
    return json.dumps(doc, indent=2, allow_nan=False) + "\n"


def csv_text(header: Sequence[str], rows: Iterable[Sequence[JsonScalar]]) -> str:
    buf = io.StringIO()
    writer = csv.writer(buf, lineterminator="\n")
    writer.writerow(header)
    for row in rows:
        writer.writerow([_cell(v) for v in row])
    return buf.getvalue()


def _cell(v: JsonScalar) -> JsonScalar:
    if isinstance(v, float):
        if not math.isfinite(v):
            raise ValueError("non-finite value in CSV output")
        return repr(v)
    if isinstance(v, str):  # text, never a number: no spreadsheet formula, no control characters
        return csv_text_cell(v)
    return v


def flatten(d: JsonObject, prefix: str = "") -> dict[str, JsonScalar]:
    """{"pinion": {"teeth": 21}} -> {"pinion_teeth": 21}; lists are left out."""
    flat: dict = {}
    for k, v in d.items():
        name = f"{prefix}{k}"
        if isinstance(v, dict):
            flat.update(flatten(v, name + "_"))
        elif not isinstance(v, (list, tuple)):
            flat[name] = v
    return flat


def design_csv(result: DesignResult) -> str:
    """One row per stage, nested objects flattened (``pinion_pitch_diameter_mm``)."""
    rows = [flatten(_allowance_columns({k: v for k, v in _named_meshes(s).items() if not (k == "rating" and v is None)}))
            for s in _design_doc(result)["stages"]]
    if any("type" in r for r in rows):  # a train of mixed kinds: every row names its kind (parallel rows too)
        for r, st in zip(rows, result.stages, strict=True):
            r.setdefault("type", st.type)
    # every row's columns once, in order of first appearance: a later stage's own columns (a planetary's, a
    # plug-in kind's, allowances the first stage lacks) after the first's, once however many stages have them
    header = list(dict.fromkeys(h for r in rows for h in r))
    return csv_text(header, ([r.get(h, "") for h in header] for r in rows))


def design_bearings_csv(result: DesignResult) -> str:
    """``gearcli design --table bearings``: the design JSON's ``bearings``, a row each."""
    return bearings_csv(_design_doc(result).get("bearings", []))


def simulation_bearings_csv(result: SimulationResult) -> str:
    """``gearcli simulate --table bearings``: the run's ``summary.bearings``, a row each."""
    return bearings_csv(plain(result.extra.get("bearings", [])) if result.extra else [])


def bearings_csv(docs: JsonValue) -> str:
    """One row per ``[[bearing]]`` (``--table bearings``): ``bearing`` (1-based in ``[[bearing]]`` order, the j of the
    ``bearing{j}_radial_N`` channels and of the warnings' ``bearing``), then the bearing's
    JSON keys by their JSON names, objects flattened (``radial_N_max``), a list of per-duty-point values as one
    column per point, 1-based in the order of ``life.points`` (``kappa_points_2``); a key a bearing lacks (no C_0,
    no C_u) is an empty cell."""
    rows: list[dict[str, JsonScalar]] = []
    for j, doc in enumerate(docs if isinstance(docs, list) else []):
        assert isinstance(doc, dict)
        row: dict[str, JsonScalar] = {"bearing": j + 1}
        for key, value in doc.items():
            if isinstance(value, dict):
                row.update(flatten(value, key + "_"))
            elif isinstance(value, (list, tuple)):
                row.update({f"{key}_{i}": _scalar(v) for i, v in enumerate(value, start=1)})
            else:
                row[key] = _scalar(value)
        rows.append(row)
    header: list[str] = []
    for row in rows:
        header += [h for h in row if h not in header]
    return csv_text(header, ([_blank(r.get(h)) for h in header] for r in rows))


def _blank(v: JsonScalar | None) -> JsonScalar:
    return "" if v is None else v


def _scalar(v: JsonValue) -> JsonScalar:
    assert not isinstance(v, (list, tuple, dict)), "a bearing's JSON nests no deeper than one list or object"
    return v  # type: ignore[return-value]


def _named_meshes(stage: _Doc) -> _Doc:
    """A planetary stage's ``meshes`` list as ``{name: mesh}`` (CSV columns ``sun_planet_...``)."""
    if "meshes" not in stage:
        return stage
    return {**{k: v for k, v in stage.items() if k != "meshes"},
            **{m["name"]: {k: v for k, v in m.items() if k != "name"} for m in stage["meshes"]}}


def simulation_csv(result: SimulationResult) -> str:
    """One row per output sample: ``time_s`` then the channels in contract order."""
    shown = channels(named(result), of_result(result))
    header = ["time_s", *shown]
    data = np.column_stack([result.time_s, *shown.values()])
    if not np.all(np.isfinite(data)):
        raise ValueError("non-finite value in CSV output")
    buf = io.StringIO()
    buf.write(",".join(header) + "\n")
    np.savetxt(buf, data, delimiter=",", fmt="%.10g")
    return buf.getvalue()
