"""A two-stage helical reducer with lightly damped meshes (mesh damping ratio 1e-4), written once for the tests of
Radau's numerical damping (test_radau_damped_ringing.py) and of windows with too few samples
(test_window_too_few_samples.py): its start rings the 808 Hz and 1805 Hz mesh modes by ~8 % of the static F_t
through the window 0.08-0.2 s."""

SCENE = """
title = "two-stage helical reducer, lightly damped meshes"
[materials.steel]
density_kg_m3 = 7850
youngs_modulus_MPa = 2.06e5
poisson_ratio = 0.3
[[stage]]
normal_module_mm = 3
normal_pressure_angle_deg = 20
helix_angle_deg = 15
pinion = { teeth = 19, face_width_mm = 45, hand = "left",  material = "steel" }
gear   = { teeth = 77, face_width_mm = 42, hand = "right", material = "steel" }
[[stage]]
normal_module_mm = 5
normal_pressure_angle_deg = 20
helix_angle_deg = 12
pinion = { teeth = 23, face_width_mm = 70, hand = "right", material = "steel" }
gear   = { teeth = 71, face_width_mm = 66, hand = "left",  material = "steel" }
[contact]
damping_ratio = 1e-4
[input]
speed_rpm = 1480
ramp_s = 0.05
[load]
torque_Nm = 1100
ramp_s = 0.05
[simulation]
duration_s = 0.2
steps = 4000
method = "Radau"
rtol = 1e-3
"""
