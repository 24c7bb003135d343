"""Shaft orders of a planetary stage's members (trial tr27a, 2026-12-01). A shaft order acts through the meshes of the
gears its shaft carries (docs/output.md, "modes"): the sun's through the sun meshes, the ring's through the ring meshes,
the carrier's through every planet mesh (its planets mesh with both). Every member of a planetary stage stood for the
stage's first connector, planet 1's sun mesh, so with the sun held and the carrier driving, the carrier's 1x and the
ring's 1x against the drum's mode on its coupling were weighed by a sun mesh that holds 1/150 of a ring mesh's share
(the held sun's mesh barely deflects there): participation and resonant gain 150 times too small.

The reference is a hand-built torsional model (docs/physics.md, "Planetary stages": absolute angles, δ_sp = r_bp θ_p
- r_c cos α θ_c with the sun held, δ_rp = r_br θ_r - r_bp θ_p - r_c cos α θ_c, the carrier with its planets' N m_p
r_c²), its undamped free modes and each connector's share k (Rφ)² / Σ of a mode's strain energy."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import scipy.linalg
from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli

SCENE = """
title = "sun held, carrier in (torque drive), ring out to a drum"
[input]
speed_rpm = 600
drive = "torque"
torque_Nm = 1285.7142857142858   # the load 1000 N m at the ring times its speed over the carrier's, 1 + 20/70
[load]
torque_Nm = 1000
inertia_kg_m2 = 40
coupling_stiffness_Nm_rad = 2.0e4
coupling_damping_Nms_rad = 50
[contact]
stiffness = 5.0e5
exponent = 1.0
damping_ratio = 0.05
[[stage]]
type = "planetary"
carrier = { inertia_kg_m2 = 0.5 }
ring = { teeth = 70, face_width_mm = 40, inertia_kg_m2 = 10.0 }   # with the drive's pinion or drum flange
planet = { teeth = 25, face_width_mm = 40, count = 3, inertia_kg_m2 = 0.05, mass_kg = 3.0 }
sun = { teeth = 20, face_width_mm = 40, inertia_kg_m2 = 0.02 }     # held: its inertia plays no part
normal_module_mm = 4
input = "carrier"
fixed = "sun"
"""


def _hand_modes():
    """Frequencies (Hz) and strain-energy shares (mode x connector: planet j sun, planet j ring, ..., coupling)."""
    cos_a = math.cos(math.radians(20.0))
    r_p, r_r, r_c = 25 * 4 / 2 * cos_a / 1e3, 70 * 4 / 2 * cos_a / 1e3, (20 + 25) * 4 / 2 * cos_a / 1e3
    a_w = (20 + 25) * 4 / 2 / 1e3
    J = np.array([0.5 + 3 * 3.0 * a_w**2, 0.05, 0.05, 0.05, 10.0, 40.0])  # carrier, planets 1-3, ring, drum
    rows, k = [], []
    for j in range(3):
        sun = np.zeros(6)
        sun[[0, 1 + j]] = -r_c, r_p
        ring = np.zeros(6)
        ring[[0, 1 + j, 4]] = -r_c, -r_p, r_r
        rows += [sun, ring]
        k += [5e8, 5e8]
    coupling = np.zeros(6)
    coupling[[4, 5]] = 1.0, -1.0
    rows.append(coupling)
    k.append(2e4)
    R, k = np.array(rows), np.array(k)
    w2, phi = scipy.linalg.eigh(R.T @ (k[:, None] * R), np.diag(J))
    strain = k[:, None] * (R @ phi) ** 2
    return np.sqrt(np.clip(w2, 0.0, None)) / (2 * math.pi), (strain / np.maximum(strain.sum(axis=0), 1e-300)).T


def test_member_shaft_orders_act_through_that_members_meshes(tmp_path: Path):
    path = tmp_path / "scene.toml"
    path.write_text(SCENE, encoding="utf-8")
    res = CliRunner().invoke(cli, ["modes", str(path), "--format", "json", "-q"])
    assert res.exit_code == 0, res.output
    modes = json.loads(res.stdout)["boundaries"]["free"]
    f, shares = _hand_modes()
    assert_allclose([m["frequency_Hz"] for m in modes[1:]], f[1:], rtol=1e-9)
    drum = modes[1]  # the drum on its coupling, 7.9 Hz: crossed by the carrier's 1x (600 rpm) and the ring's
    assert 7.0 < drum["frequency_Hz"] < 9.0
    s = shares[1]
    sun_meshes, ring_meshes = s[0:6:2], s[1:6:2]
    assert ring_meshes.max() > 50 * sun_meshes.max()  # the held sun's meshes barely deflect in it
    crossing = {c["excitation"]: c for c in drum["crossings"]}
    carrier, ring = crossing["shaft 1 1x"], crossing["shaft 2 1x"]
    assert_allclose(carrier["input_speed_rpm"], 60 * f[1], rtol=1e-9)
    assert_allclose(ring["input_speed_rpm"], 60 * f[1] / (1 + 20 / 70), rtol=1e-9)
    # the largest share among the meshes the member's gears take part in (the carrier: all six; the ring: its three)
    assert_allclose(carrier["participation"], s[:6].max(), rtol=1e-6)
    assert_allclose(ring["participation"], ring_meshes.max(), rtol=1e-6)
    assert_allclose(carrier["amplification"], carrier["participation"] / (2 * drum["damping_ratio"]), rtol=1e-12)
