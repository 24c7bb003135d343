"""The Campbell diagram of a planetary with identical planets (trial tr27a, 2026-12-01): its N - 1 = 2 planet modes
share one frequency, ω² = (k_sp + k_rp) r_bp² / J_p with the sun and the carrier at rest (docs/physics.md,
"Planetary stages"). With equal sun and ring mesh stiffness and the sun held
(clamped input) the planets' in-phase motion leaves the carrier at rest too (its levers on the two meshes are equal,
r_bs + r_bp = r_br - r_bp), so all three planet motions meet there: modes 1-3. The figure labelled each of them on
the same line, one text drawn over another, each naming the planet the eigensolver's basis happened to favour
("stage 1 planet 1 sun and ring meshes" over "stage 1 planet 3 ..."), and the crossing near the nominal speed once
per mode at one point ("stage 1 mesh 2x × mode 1" over "... × mode 2"). A repeated mode is one line with one label,
"modes 1-3 (repeated)", naming the planets together as the resonance warning does (their eigenspace's strain
energy: identical planets hold equal shares)."""

from __future__ import annotations

import math
import re
from pathlib import Path

import pytest

from gearcli.config import load_design
from gearcli.design import compute_design
from gearcli.io.units import OutputUnits
from gearcli.model.assembly import Layout
from gearcli.model.modes import campbell_data
from gearcli.scene import spec_from_design

pytest.importorskip("matplotlib")

SCENE = """
title = "planetary 20/25/70, three identical planets, ring held, sun in"
[input]
speed_rpm = 1500
[load]
torque_Nm = 300
[contact]                      # linear, 5e5 N/mm on every mesh (spur: along the transverse line of action too)
damping_ratio = 0.05
exponent = 1.0
stiffness = 5.0e5
[[stage]]
type = "planetary"
normal_module_mm = 4
fixed = "ring"
input = "sun"
sun    = { teeth = 20, face_width_mm = 40, inertia_kg_m2 = 0.02 }
planet = { teeth = 25, face_width_mm = 40, count = 3, inertia_kg_m2 = 0.09, mass_kg = 3.0 }
ring   = { teeth = 70, face_width_mm = 40 }
carrier = { inertia_kg_m2 = 0.5 }
"""


def _figure(tmp_path: Path):
    from gearcli.io.campbell import campbell_figure

    path = tmp_path / "scene.toml"
    path.write_text(SCENE, encoding="utf-8")
    cfg = load_design(str(path), []).design
    data = campbell_data(Layout.of(spec_from_design(cfg, compute_design(cfg))))
    return campbell_figure(data, OutputUnits("rpm", "Nm"), cfg.title).axes[0]


def test_repeated_planet_modes_are_one_line_with_one_label(tmp_path):
    # by hand: the planet's base radius r_bp = z m cos(20°) / 2, both meshes 5e5 N/mm = 5e8 N/m (linear, spur)
    r_bp = 25 * 4.0 * math.cos(math.radians(20.0)) / 2 / 1000.0
    f_planet = math.sqrt((5e8 + 5e8) * r_bp**2 / 0.09) / (2 * math.pi)  # 788.2 Hz
    # the stage's 2x mesh order: z_s (n_s - n_c) / 60 with n_c = n_s / (1 + 70/20), sequential (2 x 20 / 3 no integer):
    # it drives the planet modes; it meets them at 60 f / (2 x 20 x (1 - 1/4.5)) rpm, within 10 % of 1500
    meets = 60 * f_planet / (2 * 20 * (1 - 1 / 4.5))
    assert abs(meets / 1500 - 1) < 0.1
    ax = _figure(tmp_path)
    labels = [t for t in ax.texts if re.match(r"modes? \d", t.get_text())]
    at = [(round(t.xy[0], 6), round(t.xy[1], 6)) for t in labels]
    assert len(set(at)) == len(at), [t.get_text() for t in labels]  # no label drawn over another
    planet = [t.get_text() for t in labels if f"{f_planet:.4g} Hz" in t.get_text()]
    assert len(planet) == 1, planet
    assert re.fullmatch(rf"modes 1-3 \(repeated\): {f_planet:.4g} Hz \(stage 1 planets 1, 2, 3 sun and ring meshes, "
                        r"ζ [0-9.]+ %\)", planet[0]), planet
    crossing = [t.get_text() for t in ax.texts if t.get_text().startswith("stage 1 mesh 2x")]
    assert crossing == ["stage 1 mesh 2x × modes 1-3 (repeated)"]
    lines = [ln for ln in ax.get_lines() if ln.get_color() == "k" and len(set(ln.get_ydata())) == 1]
    assert sum(abs(ln.get_ydata()[0] / f_planet - 1) < 1e-9 for ln in lines) == 1


SUN_HELD = """
title = "sun held, carrier driven by a torque, ring out to a drum on a soft coupling"
[[stage]]
type = "planetary"
normal_module_mm = 4
input = "carrier"
fixed = "sun"
planet = { teeth = 25, count = 3, face_width_mm = 40, mass_kg = 3.0, inertia_kg_m2 = 0.05 }
sun = { teeth = 20, face_width_mm = 40 }
ring = { teeth = 70, face_width_mm = 40, inertia_kg_m2 = 10.0 }
carrier = { inertia_kg_m2 = 0.5 }
[contact]
stiffness = 5.0e5
exponent = 1.0
damping_ratio = 0.05
[input]
drive = "torque"
speed_rpm = 1500
torque_Nm = 1285.7142857142858
[load]
torque_Nm = 1000
inertia_kg_m2 = 40
coupling_stiffness_Nm_rad = 2.0e4
coupling_damping_Nms_rad = 50
"""


def test_close_modes_labels_do_not_overlap(tmp_path):
    """Sun held, the carrier driving: the two planet modes at ω² = (k_sp + k_rp) r_bp² / J_p = 1057.5 Hz and the planets'
    in-phase mode 1.7 % above (the carrier moves in it) lie less than a line of text apart on the log axis (7.8 Hz to
    2 kHz); their labels were drawn over each other. Six bodies, one rigid mode, the planet pair repeated: four
    labelled lines, none over another."""
    from gearcli.io.campbell import campbell_figure

    path = tmp_path / "scene.toml"
    path.write_text(SUN_HELD, encoding="utf-8")
    cfg = load_design(str(path), []).design
    data = campbell_data(Layout.of(spec_from_design(cfg, compute_design(cfg))), "free")
    fig = campbell_figure(data, OutputUnits("rpm", "Nm"), cfg.title)
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    ax = fig.axes[0]
    labels = [t for t in ax.texts if re.match(r"modes? \d", t.get_text())]
    lines = [line for t in labels for line in t.get_text().split("\n")]
    assert len(lines) == 4, lines
    r_bp = 25 * 4.0 * math.cos(math.radians(20.0)) / 2 / 1000.0
    f_planet = math.sqrt((5e8 + 5e8) * r_bp**2 / 0.05) / (2 * math.pi)
    assert sum(line.startswith(f"modes 4-5 (repeated): {f_planet:.4g} Hz") for line in lines) == 1, lines
    boxes = [t.get_window_extent(renderer) for t in labels]
    for i, a in enumerate(boxes):
        for b in boxes[i + 1:]:
            assert not a.overlaps(b), [t.get_text() for t in labels]
