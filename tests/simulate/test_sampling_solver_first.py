"""A sampling warning whose statistic the solver leaves unresolved too names the rtol first.

A 2-DOF chain (a soft input coupling, a linear spur mesh of 2e5 N/mm, a 2 µm transmission error at 2 kHz mesh
frequency) run by DOP853 at rtol 1e-3: its window min and max are off by more than the mean (statistics_unresolved,
rtol 1e-7 named), and the parabola between the samples reads that noise as undersampling: it asked for
simulation.steps=310000 (the window) and more for the run's peak. The same 20,000 samples at rtol 1e-7 are resolved
(no sampling warning at all), so the steps asked for were the unresolved solution's, not the scene's. Its window
(0.16-0.6 s, settled with 0.23 % of the static force left) still holds the coupling mode's start-up: max 2037.97 N and
min 1295.49 N against the periodic steady state's 2034.96 and 1298.55 N (1.8e-3 of the 1666.7 N mean), which that
run warns as the transient's (``transient_N``; gearcli.simulate.leftover), not the solver's or the samples'.
"""

from __future__ import annotations

from gearcli import api
from gearcli.simulate import run_simulation

SCENE = """
[materials]
steel = { density_kg_m3 = 7800, youngs_modulus_MPa = 2.07e5, poisson_ratio = 0.29 }

[[stage]]
normal_pressure_angle_deg = 20
normal_module_mm = 3
gear   = { teeth = 40, face_width_mm = 20, hand = "spur", material = "steel", inertia_kg_m2 = 4e-3 }
pinion = { teeth = 20, face_width_mm = 20, hand = "spur", material = "steel", inertia_kg_m2 = 1e-3 }
mesh = { stiffness = 2e5, exponent = 1, damping_ratio = 0.02, transmission_error_um = [2.0] }

[input]
speed_rpm = 6000
ramp_s = 0.05
coupling_stiffness_Nm_rad = 1000
coupling_damping_Nms_rad = 0.1
inertia_kg_m2 = 0.01

[load]
torque_Nm = 100
ramp_s = 0.05

[simulation]
duration_s = 0.6
steps = 20000
method = "DOP853"
"""

SAMPLING = ("statistics_undersampled", "peak_undersampled")


def _run(path, rtol: float):
    loaded = api.load(str(path), [f"simulation.rtol={rtol!r}"])
    return run_simulation(loaded.design, api.design(loaded))


def test_the_sampling_fix_of_an_unresolved_run_is_the_rtol(tmp_path):
    path = tmp_path / "chain.toml"
    path.write_text(SCENE, encoding="utf-8")
    loose = _run(path, 1e-3)
    codes = {d.code: d for d in loose.diagnostics if "transient_N" not in d.data}  # the solver's, the samples'
    assert "statistics_unresolved" in codes and "peak_unresolved" in codes
    sampled = [d for d in loose.diagnostics if d.code in SAMPLING]
    assert {d.code for d in sampled} == set(SAMPLING)
    for d in sampled:  # the rtol first, never "steps=N would resolve it" or "cannot resolve it"
        assert "simulation.rtol first" in d.message and "would resolve it" not in d.message, d.message
        assert "cannot resolve" not in d.message
    # the reference: the rtol the solver's warning names, on the same samples, needs no more of them
    named = codes["statistics_unresolved"].data["rtol"]
    assert isinstance(named, float) and named <= 1e-6
    tight = _run(path, named)
    assert not any(d.code in SAMPLING + ("statistics_unresolved",) and "transient_N" not in d.data
                   for d in tight.diagnostics), [d.message for d in tight.diagnostics if d.code in SAMPLING]
