"""Planet mesh phases follow the stage's sense of rotation (session 24, tr31b).

``planet.angles_deg`` (and the equal spacing 360 j / N) place the planets clockwise from the housing's y seen from
the input end, the frame of ``[input] rotation`` and of the shaft statics (docs/physics.md, "Shaft statics and
bearings"). Parker & Lin's phasing (planet j's sun mesh leads planet 1's by z_s psi_j / 360 mesh cycles, its ring
mesh by -z_r psi_j / 360) measures psi_j in the direction the stage turns: in a stage whose input member turns
counter-clockwise, planet j is -psi_j ahead of planet 1. The model took the housing angle whatever the sense, so a
counter-clockwise train was phased as its mirror image: the exact mirror of a clockwise train (rotation, every
hand, every centre angle and planet angle mirrored) simulated different planet loads (std of the sun-mesh F_t 4 %
apart on a 20/28/76 stage behind a helical stage), where a mirror image must give the same forces.

References: the phases by hand (z_s s psi_j / 360 with s the stage's sense: [input] rotation, reversed by each
parallel stage before it), and the mirror symmetry of the equations of motion.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli import api
from gearcli.cli import cli

STEP = 360.0 / (20 + 76)  # the planets assemble at whole multiples of 3.75 deg

PLANETARY = """
[[stage]]
type = "planetary"
normal_module_mm = 3
normal_pressure_angle_deg = 20
helix_angle_deg = 12
sun    = {{ teeth = 20, face_width_mm = 40, hand = "{sun}", material = "steel" }}
planet = {{ teeth = 28, face_width_mm = 38, hand = "{planet}", material = "steel", count = 3{angles}, position_error_um = [0, 6, -4] }}
ring   = {{ teeth = 76, face_width_mm = 40, hand = "{planet}", material = "steel" }}
carrier = {{ inertia_kg_m2 = 0.05 }}
fixed = "ring"
input = "sun"
"""
PARALLEL = """
[[stage]]
normal_module_mm = 2.5
normal_pressure_angle_deg = 20
helix_angle_deg = 14
center_angle_deg = {phi}
pinion = {{ teeth = 19, face_width_mm = 30, hand = "{pinion}", material = "steel" }}
gear   = {{ teeth = 47, face_width_mm = 28, hand = "{gear}", material = "steel" }}
"""
REST = """
[materials.steel]
density_kg_m3 = 7800
youngs_modulus_MPa = 2.07e5
poisson_ratio = 0.29

[contact]
transmission_error_um = [2.0]

[input]
speed_rpm = 1500
ramp_s = 0.03
rotation = "{rotation}"

[load]
torque_Nm = 1500
ramp_s = 0.03

[simulation]
duration_s = 0.12
steps = 4800
engine = "python"
"""


def _scene(tmp_path: Path, name: str, *, rotation: str, parallel_first: bool, angles: list[float] | None,
           mirrored: bool = False) -> str:
    left, right = ("right", "left") if mirrored else ("left", "right")
    given = "" if angles is None else f", angles_deg = [{', '.join(repr(a) for a in angles)}]"
    text = 'title = "phasing"\n'
    if parallel_first:
        text += PARALLEL.format(phi=-35 if mirrored else 35, pinion=right, gear=left)
    text += PLANETARY.format(sun=left, planet=right, angles=given) + REST.format(rotation=rotation)
    path = tmp_path / f"{name}.toml"
    path.write_text(text)
    return str(path)


def _phases(path: str) -> list[tuple[float, float]]:
    loaded = api.load(path)
    spec = api.model_spec(loaded.design, api.design(loaded))
    stage = next(m for m in spec.stage_models if hasattr(m, "mesh_phase_cycles"))
    return [(stage.mesh_phase_cycles(j, "sun"), stage.mesh_phase_cycles(j, "ring")) for j in range(3)]


def _by_hand(sense: int, angles: list[float]) -> list[tuple[float, float]]:
    """Parker & Lin with psi_j measured in the stage's running direction: sense x (housing angle - planet 1's)."""
    return [(20 * sense * (a - angles[0]) / 360.0, -76 * sense * (a - angles[0]) / 360.0) for a in angles]


@pytest.mark.parametrize(("rotation", "parallel_first", "sense"), [
    ("cw", False, 1), ("ccw", False, -1),
    ("cw", True, -1),  # a parallel stage before the planetary reverses its input's sense
    ("ccw", True, 1),
])
@pytest.mark.parametrize("angles", [None, [0.0, 31 * STEP, 64 * STEP]])
def test_planet_mesh_phases_are_measured_in_the_stage_s_running_direction(tmp_path, rotation, parallel_first,
                                                                          sense, angles):
    path = _scene(tmp_path, "s", rotation=rotation, parallel_first=parallel_first, angles=angles)
    housing = angles if angles is not None else [0.0, 120.0, 240.0]  # equal spacing: 360 j / N
    assert_allclose(_phases(path), _by_hand(sense, housing), rtol=1e-12, atol=1e-12)


def _planets(path: str) -> list[dict]:
    res = CliRunner().invoke(cli, ["simulate", path, "--format", "json"], catch_exceptions=False)
    assert res.exit_code == 0, res.stderr
    stages = json.loads(res.stdout)["summary"]["stages"]
    return next(s for s in stages if "planets" in s)["planets"]


def test_the_mirror_image_of_a_planetary_train_carries_the_same_planet_loads(tmp_path):
    """Mirrored in the x-y plane, a clockwise train becomes a counter-clockwise one with every hand, centre angle
    and planet angle mirrored (psi -> 360 - psi); the equations of motion are the same, so is every planet's
    sun-mesh force. Planets at 0, 116.25 and 240 deg (sequentially phased: z_s psi / 360 = 0, 6.46, 13.33
    cycles), each with its own position error, behind a helical stage (centre angle 35 deg)."""
    angles = [0.0, 31 * STEP, 64 * STEP]
    original = _planets(_scene(tmp_path, "cw", rotation="cw", parallel_first=True, angles=angles))
    mirror = _planets(_scene(tmp_path, "ccw", rotation="ccw", parallel_first=True,
                             angles=[(-a) % 360.0 for a in angles], mirrored=True))
    for a, b in zip(original, mirror, strict=True):
        for stat in ("mean", "std", "min", "max"):
            # the mirror takes the solver's very steps: 1e-13 seen; the old phasing 2e-4 .. 6e-3 apart
            assert_allclose(b["sun"]["tangential_N"][stat], a["sun"]["tangential_N"][stat], rtol=1e-9)
    assert all(p["sun"]["tangential_N"]["std"] > 300 for p in original)  # the TE and the errors load them unequally
