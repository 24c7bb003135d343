"""One spur stage on a linear viscous mesh (k = 3e5 N/mm, 5 % damping), the load applied as a step at t = 0: the
scene whose start has a closed-form step response (tests/reference/test_peak_sampling.py, tests/unit/test_rigid_start.py)
and, with a feather-light gear, a 6.6 MHz mode (tests/engine/test_course.py)."""

STEP_SCENE = """
title = "one spur stage, linear viscous mesh, the load applied as a step"
[materials.steel]
density_kg_m3 = 7800
youngs_modulus_MPa = 2.07e5
poisson_ratio = 0.3
[[stage]]
normal_module_mm = 4
normal_pressure_angle_deg = 20
pinion = { teeth = 20, face_width_mm = 30, material = "steel", inertia_kg_m2 = 0.01 }
gear   = { teeth = 40, face_width_mm = 30, material = "steel", inertia_kg_m2 = 0.05 }
[contact]
stiffness = 3e5
exponent = 1
damping_ratio = 0.05
[input]
speed_rpm = 600
ramp_s = 0.0
[load]
torque_Nm = 200
ramp_s = 0.0
[simulation]
duration_s = 0.1
steps = 4000
"""


def feather_gear(scene: str = STEP_SCENE) -> str:
    """The step scene with a 1e-9 kg m^2 gear (a 6.6 MHz mesh mode) on the Python engine."""
    light = scene.replace('inertia_kg_m2 = 0.05 }', 'inertia_kg_m2 = 1e-9 }')
    assert light != scene
    return light.replace('title = "one spur stage, linear viscous mesh, the load applied as a step"',
                         'title = "one spur stage, a 1e-9 kg m^2 gear on a linear mesh, the load applied as a step"') \
        + 'engine = "python"\n'
