"""`gearcli design` warns when a mesh order meets a drivetrain mode, naming the mode and its dominant element.

Independent reference: a motor held at its prescribed speed (speed drive) and joined by a soft coupling to
the reducer, whose meshes are ~100x stiffer than the coupling, has a coupling mode at
f = sqrt(k / J_r) / 2 pi with J_r = sum J_i rho_i^2 the reducer's inertia reflected to its input (rigid
meshes, rho_i the speed ratio of shaft i; by hand from the design's shaft inertias). Choosing k so that
this f equals the stage-3 mesh frequency z_5 n_5 / 60 puts a mesh order on the mode: design must warn.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

from click.testing import CliRunner

from gearcli.cli import cli

SEED = str(Path(__file__).resolve().parents[2] / "configs" / "concrete_mixer.toml")


def _design(*sets: str) -> tuple[dict, str]:
    args = ["design", SEED, "--format", "json"]
    for s in sets:
        args += ["--set", s]
    res = CliRunner().invoke(cli, args)
    assert res.exit_code == 0, res.stderr
    return json.loads(res.stdout), res.stderr


def test_a_coupling_mode_on_a_mesh_order_is_warned_naming_mode_and_coupling():
    seed, _ = _design()
    z = [(s["pinion"]["teeth"], s["gear"]["teeth"]) for s in seed["stages"]]
    rho = [1.0, z[0][0] / z[0][1], z[0][0] / z[0][1] * z[1][0] / z[1][1],
           z[0][0] / z[0][1] * z[1][0] / z[1][1] * z[2][0] / z[2][1]]
    inertia = [seed["stages"][0]["pinion"]["inertia_kg_m2"]]
    inertia += [seed["stages"][k]["gear"]["inertia_kg_m2"] + seed["stages"][k + 1]["pinion"]["inertia_kg_m2"]
                for k in range(2)]
    inertia += [seed["stages"][2]["gear"]["inertia_kg_m2"]]
    j_r = sum(j * r * r for j, r in zip(inertia, rho, strict=True))
    f_mesh3 = z[2][0] * 600.0 * rho[2] / 60.0  # 600 rpm input: stage 3's pinion turns at 600 rho_3 rpm
    k = j_r * (2 * math.pi * f_mesh3) ** 2
    doc, stderr = _design("input.inertia_kg_m2=0.5", f"input.coupling_stiffness_Nm_rad={k!r}")
    found = [w["message"] for w in doc["warnings"] if w["message"].startswith("resonance:")
             and "stage 3 mesh 1x" in w["message"]]
    assert found, doc["warnings"]
    assert "input coupling" in found[0] and "mode 1 " in found[0]  # the lowest mode, dominated by the coupling
    assert found[0] in stderr  # the same warning on the terminal as in the JSON


def test_the_seed_alone_has_no_drivetrain_resonance_warning():
    doc, _ = _design()
    assert not [w for w in doc["warnings"] if w["message"].startswith("resonance:")]
