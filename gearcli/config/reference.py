"""docs/design-file.md, generated from the JSON Schema (itself generated from the pydantic models), so
the reference cannot drift from what validation accepts.

Regenerate after a schema change (a test compares the committed file with this text)::

    python -m gearcli.config.reference > docs/design-file.md
"""

from __future__ import annotations

import json
import math
from typing import Any

from gearcli.config.prescan import MAX_BYTES, MAX_KEY_DEPTH, MAX_KEYS, MAX_NESTING
from gearcli.config.starter import json_schema

_TABLES = [("", "DesignFile", "The top level"), ("[materials.NAME]", "Material", "A material, referenced by name"),
           ("[[stage]]", "Stage", "One gear pair per [[stage]], in the order power flows"),
           ("stage pinion / gear", "PairGear", "`pinion = { ... }` and `gear = { ... }` of a stage"),
           ("stage basic_rack = { ... }", "BasicRack", "The basic rack profile of a stage (ISO 53)"),
           ("stage shaft = { ... }", "ShaftSpring", "The torsional spring of the shaft after a stage"),
           ('[[stage]] type = "planetary"', "PlanetaryStage", "A planetary stage (docs/physics.md)"),
           ("planetary stage sun = { ... }", "Sun", "`sun = { ... }` of a planetary stage (the keys of a gear)"),
           ("planetary stage planet = { ... }", "Planet", "The planets of a planetary stage"),
           ("planetary stage ring = { ... }", "Ring", "The internal ring gear of a planetary stage"),
           ("planetary stage carrier = { ... }", "Carrier", "The planet carrier of a planetary stage"),
           ("[contact]", "Contact", "The mesh force law"),
           ("[stage.mesh]", "ContactOverride", "Per-stage overrides of [contact]"),
           ("[input]", "Input", "The input drive"),
           ("input.motor = { ... }", "Motor", "The induction motor of `drive = \"motor\"`"),
           ("input.torque_ripple = [{ ... }]", "Ripple", "One harmonic of the input torque"),
           ("[load]", "Load", "The output load"),
           ("load.fluctuation = [{ ... }]", "Fluctuation", "One harmonic of the load torque"),
           ("[target]", "Target", "Optional: the output speed the design must reach"),
           ("[simulation]", "Simulation", "Settings of `gearcli simulate` and `gearcli report`"),
           ("[lubricant]", "Lubricant", "Optional: the gear oil (Z_L of the strength rating)"),
           ("[rating]", "Rating", "Optional: ISO 6336-2/-3 strength rating of every stage (docs/iso6336.md)"),
           ("[[bearing]]", "Bearing", "Optional: a rolling bearing under a shaft (docs/life.md)"),
           ("bearing factors = { ... }", "BearingFactors", "ISO 281 equivalent-load factors of a bearing"),
           ("bearing static_factors = { ... }", "StaticFactors", "ISO 76 static equivalent-load factors of a bearing "
            "(docs/bearings.md)"),
           ("[[duty]]", "Duty", "Optional: one operating point of the duty cycle of `gearcli life` (docs/life.md)")]


_TYPES = {"number": "number", "integer": "integer", "boolean": "true/false", "string": "string"}


def _num(v: Any) -> str:
    if isinstance(v, float) and v.is_integer() and abs(v) < 1e7:
        return str(int(v))
    return f"{v:g}" if isinstance(v, float) else json.dumps(v)


def _bound(v: Any, *, upper: bool) -> str:
    """A range's bound as :func:`_num` prints it, rounded inward where that text is not the bound itself: an
    upper bound down, a lower one up, so every value the reference shows inside the range validates (200000 rpm
    is 20943.951... rad/s, printed 20943.9, never 20944, which validation refuses)."""
    shown = _num(v)
    if not isinstance(v, float) or not math.isfinite(v) or v == 0 or float(shown) == v:
        return shown
    for digits in range(6, 18):
        scale = 10.0 ** (math.floor(math.log10(abs(v))) - digits + 1)
        shown = f"{(math.floor if upper else math.ceil)(v / scale) * scale:.{digits}g}"
        if (float(shown) <= v) if upper else (float(shown) >= v):
            return shown
    return repr(v)


def _kind(prop: dict, defs: dict) -> tuple[str, str]:
    """(type, allowed values) of one property."""
    if "$ref" in prop:
        return "table", ""
    options = prop.get("anyOf") or prop.get("oneOf")
    if options:
        parts = [_kind(o, defs) for o in options if o.get("type") != "null"]
        return " or ".join(p[0] for p in parts), "; ".join(p[1] for p in parts if p[1])
    if "enum" in prop:  # the schema's type where it states one: speed_exponent is an integer 0, 1 or 2
        kind = prop.get("type", "string")
        return _TYPES.get(kind, kind), ", ".join(json.dumps(v) for v in prop["enum"])
    if "const" in prop:
        return "string", json.dumps(prop["const"])
    t = prop.get("type", "any")
    if t == "object" and "additionalProperties" in prop:
        return "tables by name", ""
    if t == "array":
        items = prop.get("minItems"), prop.get("maxItems")
        count = (f"{items[0]} entries" if items[0] == items[1] else f"{items[0]} to {items[1]} entries") \
            if all(i is not None for i in items) else f"at most {items[1]} entries" if items[1] is not None else ""
        item = prop.get("items", {})
        if "$ref" in item:
            return "array of tables", count
        kind, rng = _kind(item, defs)
        plural = f"arrays of {kind[len('array of '):]}" if kind.startswith("array of ") else f"{kind}s"
        return f"array of {plural}", "; ".join(x for x in (count, f"each {rng}" if rng else "") if x)
    lo = prop.get("minimum", prop.get("exclusiveMinimum"))
    hi = prop.get("maximum", prop.get("exclusiveMaximum"))
    rng = ""
    if lo is not None or hi is not None:
        left = "(" if "exclusiveMinimum" in prop else "["
        right = ")" if "exclusiveMaximum" in prop else "]"
        rng = (f"{left}{_bound(lo, upper=False) if lo is not None else '-inf'}, "
               f"{_bound(hi, upper=True) if hi is not None else 'inf'}{right}")
    if "not" in prop:
        tiny = max(r["exclusiveMaximum"] for r in prop["not"]["anyOf"])
        rng += f"; 0 or magnitude ≥ {_num(tiny)}"
    if "maxLength" in prop:
        rng = f"at most {prop['maxLength']} characters"
    return _TYPES.get(t, t), rng


def _table(title: str, name: str, what: str, defs: dict, root: dict) -> list[str]:
    model = root if name == "DesignFile" else defs[name]
    required = set(model.get("required", []))
    about = model["description"] if model.get("description") and name != "DesignFile" else what + "."
    lines = [f"## {title or 'top level'}", "", about.replace("\n", " "), "",
             "| key | type | allowed | default |", "|---|---|---|---|"]
    for key, prop in model.get("properties", {}).items():
        kind, allowed = _kind(prop, defs)
        default = "required" if key in required else (_num(prop["default"]) if "default" in prop and
                                                     prop["default"] is not None else "—")
        if isinstance(prop.get("default"), dict):
            default = "see below"
        lines.append(f"| `{key}` | {kind} | {allowed.replace('|', '/')} | {default} |")
    return lines + [""]


def design_file_reference() -> str:
    schema = json_schema()
    defs = schema.get("$defs", {})
    out = ["# The design file (reference)", "",
           "Generated from the JSON Schema of the pydantic models by `python -m gearcli.config.reference`; "
           "`gearcli schema` prints the schema itself. Do not edit by hand.", "",
           "A design file is UTF-8 TOML (a BOM and CRLF line ends are accepted). Units are in the key names. "
           "Unknown keys are errors. Every number has bounds: far outside any real reducer, yet tight enough "
           "that a unit mistake (1e15, or a subnormal such as 1e-320) is an error naming the key and the bound. "
           "Keys that may be 0 (ramps, damping, backlash, torques) refuse a nonzero magnitude below a small "
           "threshold, shown as \"0 or magnitude ≥ …\". No float key, list or table entry accepts a subnormal "
           "number (nonzero, below 2.2e-308 in magnitude): one rule for every float of the file.", "",
           "Rules between keys (the schema states them too, in `allOf`/`anyOf`/`not`): exactly one of "
           "`speed_deg_s`, `speed_rpm`, `speed_rad_s` in `[input]`; at most one of `torque_Nm`, `torque_Nmm`, "
           "`power_kW` there, required with `drive = \"torque\"` and refused with `drive = \"speed\"`; exactly one "
           "torque in `[load]`; exactly one speed in `[target]`; `inertia_kg_m2` and `coupling_stiffness_Nm_rad` "
           "together (coupling damping needs both); a helical stage's pinion and gear have opposite hands. Rules "
           "the schema states only as text (validation enforces them): every `material` names a table of "
           "`[materials]` (a file without `[materials]` has the built-in steel; one with it defines every material it "
           "names, steel included); no more `transmission_error_phase_deg` than "
           "`transmission_error_um` entries, nor `stiffness_harmonics_phase_deg` than `stiffness_harmonics` (a "
           "stage's `[stage.mesh]` counted with what it inherits from `[contact]`); the `stiffness_harmonics` sum "
           "to less than 1 in magnitude; `input.torque_ripple` only with `drive = \"torque\"`; a shaft with "
           "`[[bearing]]` tables has exactly two of them at different positions, exactly one `locating`, and "
           "the gears on it give `axial_position_mm` (the design checks these); a `[[duty]]` point gives exactly "
           "one of `torque_Nm`, `torque_Nmm`, `power_kW`.", "",
           "## Limits", "",
           f"- file size at most {MAX_BYTES // 2**20} MiB; at most {MAX_KEYS} keys and tables; dotted keys of at "
           f"most {MAX_KEY_DEPTH} parts; arrays and inline tables nested at most {MAX_NESTING} deep. These are "
           "checked on the raw text before the TOML parser runs.",
           "- a simulation whose output would need more memory than `GEARCLI_MEMORY_LIMIT_MB` (default 2048) is "
           "refused with the estimate and the most `simulation.steps` that fit (a `steady = \"periodic\"` run holds its "
           "100000 statistics samples besides its steps: below them, none fits); one whose cost estimate is absurd "
           "(over 5e8 right-hand-side evaluations) is refused with the `simulation.duration_s` that fits (or, where not "
           "even the least duration fits, with the speeds, stiffnesses and inertias to check). Each sweep point and life "
           "duty point is checked the same way with its own values: a refused sweep point is a `failed` row with that "
           "message, a refused duty point ends `life` (exit 2) naming it.", ""]
    for title, name, what in _TABLES:
        if name == "DesignFile" or name in defs:
            out += _table(title, name, what, defs, schema)
    return "\n".join(out).rstrip() + "\n"


def undocumented_tables() -> list[str]:
    """Models of the schema that the reference has no section for (a test keeps this empty)."""
    documented = {name for _, name, _ in _TABLES}
    return sorted(set(json_schema().get("$defs", {})) - documented)


if __name__ == "__main__":  # pragma: no cover
    print(design_file_reference(), end="")
