"""The starter design file of ``gearcli init`` and the JSON Schema of ``gearcli schema``.

The starter file is the seed reducer (the numbers of ``configs/concrete_mixer.toml``), written
with tomli-w, one explanatory comment block above each table.
"""

from __future__ import annotations

from typing import Any

from gearcli.config.schema import DesignFile


def _gear(teeth: int, face_width_mm: int, hand: str) -> dict:
    return {"teeth": teeth, "face_width_mm": face_width_mm, "hand": hand, "material": "steel"}


def _stage(module: int, helix: int, pinion: dict, gear: dict) -> dict:
    return {"normal_module_mm": module, "normal_pressure_angle_deg": 20, "helix_angle_deg": helix,
            "pinion": pinion, "gear": gear}


#: The seed reducer (seed paper Table 1 and sections 3-4), as ``configs/concrete_mixer.toml`` has it.
SEED: dict[str, Any] = {
    "title": "Concrete mixer reducer, three helical stages (seed paper)",
    "materials": {"steel": {"density_kg_m3": 7800, "youngs_modulus_MPa": 2.07e5, "poisson_ratio": 0.29}},
    "stage": [
        _stage(12, 12, _gear(21, 190, "left"), _gear(51, 180, "right")),
        _stage(18, 11, _gear(17, 250, "right"), _gear(50, 240, "left")),
        _stage(25, 9, _gear(17, 320, "left"), _gear(53, 310, "right")),
    ],
    "contact": {"stiffness": "hertz", "exponent": 1.5, "damping_Ns_mm": 50, "full_damping_penetration_mm": 0.1},
    "input": {"speed_deg_s": 3600, "ramp_s": 0.18},
    "load": {"torque_Nmm": 5.31e6, "ramp_s": 0.18},
    "target": {"output_speed_rpm": 23, "tolerance_percent": 5},
    "simulation": {"duration_s": 0.5, "steps": 2000, "method": "auto", "rtol": 1e-6},
}

_HEADER = """\
# gearcli design file: the seed reducer, a three-stage helical concrete-mixer reducer.
# Units are in the key names (mm, deg, MPa, N mm, s). Edit it, then:
#   gearcli design FILE      ratios, geometry, contact ratios, stiffness, static forces
#   gearcli simulate FILE    torsional dynamics;  --set KEY=VALUE overrides any key
"""

_COMMENTS = {
    "materials": """\
# [materials.NAME]: one table per material, referred to by a gear's `material` key.
#   density_kg_m3 > 0, youngs_modulus_MPa > 0, poisson_ratio in (0, 0.5)""",
    "stage": """\
# [[stage]]: one table per gear pair, in the order power flows; the pinion drives the gear,
# and the gear of stage k shares a shaft with the pinion of stage k+1.
#   normal_module_mm > 0, normal_pressure_angle_deg in [10, 35], helix_angle_deg in [0, 45)
#   pinion / gear: teeth (whole number >= 5), face_width_mm, hand = "left" | "right" (or "spur"
#   when helix_angle_deg = 0), material; optional profile_shift, inertia_kg_m2 (default: solid disc)
#   optional: backlash_mm (normal, default 0), efficiency (0, 1], [stage.mesh] overriding [contact]""",
    "contact": """\
# [contact]: the mesh force law F = K h^exponent + damping, for every mesh. This is the seed paper's law (MSC
#   Adams IMPACT); without the table a mesh is calibrated to ISO 6336-1 at the operating point: stiffness =
#   "iso6336" (the law's tangent at the static load is ISO's mesh stiffness), exponent = 1.5, damping_ratio = 0.05.
#   stiffness = "hertz" (K = 4/3 sqrt(R) E*) | "iso6336" | K in N/mm^exponent; exponent in [1, 3];
#   damping_ratio (viscous) or damping_Ns_mm >= 0 reached at full_damping_penetration_mm > 0 (IMPACT);
#   time_varying = true scales K with the length of the contact lines over the mesh cycle""",
    "input": """\
# [input]: the drive. Exactly one of speed_deg_s, speed_rpm, speed_rad_s; ramp_s >= 0 (0 = full speed at t = 0).
#   drive = "speed" (prescribed speed, default) | "torque" (then torque_Nm, torque_Nmm or power_kW drives a free input shaft)
#   | "motor" (an induction motor from rest: motor = { rated_power_kW, rated_speed_rpm, synchronous_speed_rpm,
#   breakdown_torque_ratio, locked_rotor_torque_ratio } or { torque_speed = [[rpm, N·m], ...] };
#   starting = "direct" | "star_delta" | "soft_start" | "vfd"; the speed key is then the nominal speed)""",
    "load": """\
# [load]: torque on the output shaft, resisting its rotation (negative = load reversal).
#   Exactly one of torque_Nmm, torque_Nm, power_kW; ramp_s >= 0; application_factor K_A in [1, 10] (default 1)
#   speed_exponent = 0 | 1 | 2 (torque ~ speed^k, the torque given at the nominal output speed), or instead of
#   a torque key a table torque_speed = [[rpm, N·m], ...] of the output speed""",
    "target": """\
# [target] (optional): the output speed the design must reach; a miss is a warning.
#   Exactly one of output_speed_rpm, output_speed_deg_s; tolerance_percent in (0, 100]""",
    "simulation": """\
# [simulation]: duration_s > 0; steps = output samples - 1; rtol in [1e-13, 1e-2];
#   method = "auto" | "RK45" | "DOP853" | "Radau" | "BDF" | "LSODA"; optional window_start_s (statistics);
#   steady = "window" (default) | "periodic" (run until the response repeats, statistics over whole periods);
#   error_estimate = true (default: a check pass estimates the error of min/max/std; false skips it)""",
}


def _inline(table: dict) -> str:
    """``{ teeth = 21, hand = "left" }``, each value formatted by tomli-w."""
    import tomli_w  # lazy: `gearcli init` only (start-up time of the other commands)

    return "{ " + ", ".join(tomli_w.dumps({k: v}).strip() for k, v in table.items()) + " }"


def _stage_toml(stage: dict) -> str:
    import tomli_w  # lazy: `gearcli init` only

    scalars = {k: v for k, v in stage.items() if not isinstance(v, dict)}
    tables = "".join(f"{k} = {_inline(v)}\n" for k, v in stage.items() if isinstance(v, dict))
    return "[[stage]]\n" + tomli_w.dumps(scalars) + tables


def starter_toml() -> str:
    """A commented starter design file: the seed reducer, loadable as it is."""
    import tomli_w  # lazy: `gearcli init` only

    parts = [_HEADER + tomli_w.dumps({"title": SEED["title"]})]
    parts.append(_COMMENTS["materials"] + "\n" + tomli_w.dumps({"materials": SEED["materials"]}).strip() + "\n")
    stages = "\n".join(_stage_toml(s) for s in SEED["stage"])
    parts.append(_COMMENTS["stage"] + "\n" + stages)
    for table in ("contact", "input", "load", "target", "simulation"):
        parts.append(_COMMENTS[table] + "\n" + tomli_w.dumps({table: SEED[table]}))
    return "\n".join(parts)


def json_schema() -> dict:
    """The JSON Schema of a design file (``gearcli schema``), with a title and a description."""
    schema = DesignFile.model_json_schema()
    return {
        "$schema": "https://json-schema.org/draft/2020-12/schema",
        "title": "gearcli design file",
        "description": (
            "A multi-stage helical gear reducer for gearcli (TOML). Units are in the key names; "
            "unknown keys are errors. See docs/design-file.md."
        ),
        **{k: v for k, v in schema.items() if k not in ("title", "description")},
    }
