"""A rattling mesh's check pass starts at t = 0 (gearcli.simulate.estimate, "Span").

One helical stage (z 22/47, m_n 2.5, b 18 mm), 0.08 mm backlash, 6 N m load (F_t = 6000 / (2.5 x 47 / cos 10° / 2)
= 100.6 N static), 8 µm + 2 µm of transmission error at 880 Hz mesh frequency, near its 1485 Hz mesh mode: the flanks
separate most of the window. Two responses coexist, a periodic one that stays on the drive flank (window max
~1467 N) and one that strikes the back flank (max ~4500 N); which one the run lands on depends on the run-up's
numerical error (DOP853 at rtol 1e-6, 3e-7 and 1e-9: the first; 1e-7, 1e-8 and 1e-10: the second). The check pass
used to start 16 ms before the window (4.6 / sigma of the 3 %-damped mesh mode) from the run's own state, so it
followed the run's response: at rtol 1e-6 it estimated the max 0.42 N off (4.2e-3 of the mean) and named rtol 1e-7,
whose run is ~3000 N away. From t = 0 the check integrates the run-up too and sees the spread: 0.41 of the mean.
Measured with scipy's DOP853 (engine = "python") and numpy's default BLAS; under the test suite's OPENBLAS_CORETYPE
the rtol 1e-6 run lands on the striking response instead (max 4076 N, the 1e-10 run's 4548 N): round-off alone
picks the branch.

The step pattern picks it too, for the run and for the rtol 1e-10 reference alike. DOP853's stability radius
patched in-process over 5.8, 5.85, 5.9, 5.93, 5.95, 5.97, 6.0, 6.03 (OPENBLAS_CORETYPE=Haswell): the rtol 1e-6 run's
window max is 1467-1469 N at four radii and 2566-4196 N at the others, the reference's 1467-1643 N at four and
3167-4607 N at the others; |run - reference| of the max is 86 N (0.86 of the mean, 5.8) to 3.1 kN; the run's
estimate of its max 0.0092 (5.97), 0.027 (5.95), 0.13 (5.8) of the mean where the check pass landed on the run's
response, 9-42 where it landed on the other. So neither "more than the mean off" nor an estimate's size is the
promise: a min, max or std beyond its target against the reference is named unresolved (the max was, at every
radius), with the words that no rtol is promised (estimate.NONSMOOTH). The mean is left out: at 5.97 the check pass
landed on the run's response, estimated the mean 1e-5 off and did not name it, where it is 0.0087 of itself from the
reference on the other response (a single check pass sees no spread it does not land on; named at the other seven).
"""

from __future__ import annotations

from gearcli import api
from gearcli import diagnostics as dg
from gearcli.simulate import run_simulation
from gearcli.simulate.estimate import NO_RTOL_RESOLVES, NONSMOOTH, target

SCENE = """
[materials.steel]
poisson_ratio = 0.29
youngs_modulus_MPa = 2.07e5
density_kg_m3 = 7800

[[stage]]
helix_angle_deg = 10
backlash_mm = 0.08
normal_module_mm = 2.5
normal_pressure_angle_deg = 20
pinion = { teeth = 22, face_width_mm = 18, hand = "left", material = "steel", inertia_kg_m2 = 4e-4 }
gear   = { teeth = 47, face_width_mm = 18, hand = "right", material = "steel", inertia_kg_m2 = 6e-3 }

[contact]
transmission_error_um = [8.0, 2.0]
transmission_error_phase_deg = [0, 40]
damping_ratio = 0.03
exponent = 1.5

[input]
speed_rpm = 2400
ramp_s = 0.03

[load]
torque_Nm = 6
ramp_s = 0.03

[simulation]
duration_s = 0.3
steps = 30000
method = "DOP853"
engine = "python"  # the compiled engine's round-off differs, and a chaotic run-up amplifies it
"""


def test_a_rattling_window_is_checked_from_the_start(tmp_path):
    source = tmp_path / "rattle.toml"
    source.write_text(SCENE, encoding="utf-8")
    run, reference = (run_simulation((lo := api.load(str(source), [f"simulation.rtol={r!r}"])).design, api.design(lo))
                      for r in (1e-6, 1e-10))
    st, ref = run.stages[0], reference.stages[0]
    assert st.contact_loss_fraction > 0.5  # it rattles
    assert run.solver.check_pass["from_s"] == 0.0
    warned = [d for d in run.diagnostics if d.code == dg.STATISTICS_UNRESOLVED]
    named = set(warned[0].data["statistics"]) if warned else set()
    beyond = {q for q in ("min", "max", "std")  # against DOP853 at rtol 1e-10, whichever response each run lands on
              if abs(getattr(st.tangential_N, q) - getattr(ref.tangential_N, q)) > target(q) * abs(ref.tangential_N.mean)}
    assert beyond <= named, (beyond, named)
    # and the warning promises no rtol: where responses coexist, a tighter one may land on another (or none is predicted)
    assert not named or any(words in warned[0].message for words in (NONSMOOTH.split("{")[0], NO_RTOL_RESOLVES))
