"""The full-damping-depth warning belongs to the IMPACT law only (DESIGN §13: the default viscous law has no
full-damping depth). Found by the audit: every default-law run whose transient went deeper than 0.1 mm warned
"beyond the full-damping depth 0.1 mm (the damping saturates there)" about a ramp it does not use."""

from __future__ import annotations

import math

import numpy as np

from gearcli import diagnostics as dg
from gearcli.model import DriveSpec, LoadSpec, MeshSpec, ModelSpec
from gearcli.simulate.stats import contact_warnings

DEG = math.pi / 180.0


def spec(damping_ratio: float | None) -> ModelSpec:
    mesh = MeshSpec(base_radius_pinion_m=0.06, base_radius_gear_m=0.15, base_helix_angle_rad=10 * DEG,
                    transverse_pressure_angle_rad=20.3 * DEG, helix_angle_rad=10.6 * DEG, stiffness_N_m_e=2e8,
                    exponent=1.5, damping_Ns_m=5e4, full_damping_m=1e-4, contact_ratio=1.6, overlap_ratio=0.0,
                    pinion_teeth=20, damping_ratio=damping_ratio)
    return ModelSpec((mesh,), (0.3, 2.5), DriveSpec("speed", 50.0), LoadSpec(300.0))


def codes(s: ModelSpec) -> list[str]:
    # a transient 0.3 mm deep (3x the 0.1 mm full-damping depth), a static approach of 5 um; always on the drive
    # flank, so no contact-loss warning; the module is unknown (0) so the 10 %-of-module check stays silent
    pen = np.array([5e-6, 3e-4, 5e-6])
    return [d.code for d in contact_warnings(s, np.ones(3, dtype=bool), [pen], np.array([5e-6]))]


def test_an_impact_damped_mesh_warns_when_a_transient_passes_the_full_damping_depth():
    assert codes(spec(None)) == [dg.PENETRATION_BEYOND_DAMPING]


def test_a_viscous_mesh_has_no_full_damping_depth_to_warn_about():
    assert codes(spec(0.05)) == []
