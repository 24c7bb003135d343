"""The up-front cost guard's advice is a duration it accepts (gearcli/config/bounds.py, check_cost).

The refusal names the longest ``simulation.duration_s`` that fits its limit, to three digits. It rounded to nearest,
so a fit of 746.6 s was printed "≤ 747", and 747 s was refused again with the same advice. The limit here by hand:
one linear spur mesh behind a speed drive (the pinion's motion given: J_p infinite) rings at
omega = sqrt(k r_bg^2 / J_g); the guard allows 30 omega T (1e-6 / rtol)^0.2 <= 5e8 right-hand sides.
"""

from __future__ import annotations

import math
import re

import pytest

from gearcli.config import load_design
from gearcli.config.bounds import check_cost
from gearcli.core.text import rounded_down, rounded_up
from gearcli.design import compute_design
from gearcli.errors import ResourceError

K_N_MM = 4e5  # linear law, N/mm: k = 4e8 N/m along the (spur) line of action
R_BG = 60 * 4 * math.cos(math.radians(20)) / 2e3  # gear base radius, m
FIT_S = 746.6  # the duration the hand limit gives, chosen to round up at three digits
OMEGA = 5e8 / (30.0 * FIT_S)  # rad/s
J_G = K_N_MM * 1e3 * R_BG**2 / OMEGA**2


def scene(tmp_path, duration_s: float):
    path = tmp_path / "long.toml"
    path.write_text(
        'title = "long run"\n'
        "[[stage]]\nnormal_module_mm = 4\npinion = { teeth = 20, face_width_mm = 40, inertia_kg_m2 = 1e-3 }\n"
        f"gear = {{ teeth = 60, face_width_mm = 40, inertia_kg_m2 = {J_G!r} }}\n"
        f"[contact]\nstiffness = {K_N_MM:g}\nexponent = 1\ndamping_ratio = 0.02\n"
        "[input]\nspeed_rpm = 1500\nramp_s = 0.1\n[load]\ntorque_Nm = 100\nramp_s = 0.1\n"
        f"[simulation]\nduration_s = {duration_s:g}\nsteps = 2000\nrtol = 1e-6\n")
    cfg = load_design(str(path)).design
    return cfg, compute_design(cfg)


def test_the_refusal_advises_a_duration_that_the_guard_accepts(tmp_path):
    with pytest.raises(ResourceError) as err:
        check_cost(*scene(tmp_path, 3600.0), source="long.toml")
    advised = float(re.search(r"simulation\.duration_s ≤ ([0-9.e+-]+)", str(err.value)).group(1))
    assert FIT_S * (1 - 1e-2) <= advised <= FIT_S  # three digits, on the side that fits: 746
    check_cost(*scene(tmp_path, advised), source="long.toml")  # accepted
    with pytest.raises(ResourceError):  # and the limit is where the hand calculation puts it
        check_cost(*scene(tmp_path, FIT_S * 1.001), source="long.toml")


def test_rounded_down_keeps_the_safe_side_of_a_limit():
    assert rounded_down(746.6) == 746 and rounded_down(0.7469) == 0.746 and rounded_down(1.23e-4) == 1.23e-4
    assert rounded_down(2.1635039, 4) == 2.163 and rounded_up(2.1635039, 4) == 2.164  # the two sides of one figure
