"""``gearcli life`` on the trial's own duties (branch t9d), the steps themselves: a step's `set` that would
write the step's or the duty's own keys, names that must be the step's own, a zero-load step on the dynamic
route (a stage at rest), and starts whose cycles, damage and bearing level are counted by hand. Scenes and
hand formulas: tests/life/engineer_duties.py."""

from __future__ import annotations

import math

import pytest
from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli
from tests.life.engineer_duties import (
    ALPHA,
    PAR_BASE,
    ZNT_CASE,
    U,
    a_iso,
    cycles_to_failure,
    duty_text,
    nu_1,
    nu_at,
    run_life,
)
from tests.life.scenes import design_of

# --- the duty's own keys in a step's set ---------------------------------------------------------------------

STEP = '\n[[duty]]\nname = "x"\nhours = 20000\ntorque_Nm = 900\nspeed_rpm = 1000\n'


@pytest.mark.parametrize(("set_line", "named"), [
    # a nested table wrote the step's own speed and torque past the check: the table and JSON reported 1000 rpm
    # and 900 N·m while the damage was computed at 3 rpm / 3 N·m
    ('set = { input = { speed_rpm = 3 } }', "input.speed_rpm"),
    ('set = { load = { torque_Nm = 3, ramp_s = 0.05 } }', "load.torque_Nm"),
    ("set = { 'input.\"speed_rpm\"' = 3 }", 'input."speed_rpm"'),  # a quoted segment, as --set reads it
    ('set = { "stage[0].gear.teeth" = 61, "load.application_factor" = 2 }', "load.application_factor"),
    # the duty's verdicts read the first step's file: its set moved the duty's required life and minimum safety
    ('set = { "rating.required_life_h" = 5 }', "rating.required_life_h"),
    ('set = { rating = { min_safety_pitting = 3 } }', "rating.min_safety_pitting"),
    ('set = { "stage[0].gear.teeth" = 61, "bearing[0].reliability_percent" = 95 }', "bearing[0].reliability_percent"),
    ('set = { "duty.0.hours" = 5 }', "duty.0.hours"),
    ('set = { bearing = [] }', "bearing"),
])
def test_a_step_may_not_set_the_points_or_the_dutys_own_keys(tmp_path, set_line, named):
    path = tmp_path / "scene.toml"
    path.write_text(PAR_BASE + STEP + set_line + "\n")
    res = CliRunner().invoke(cli, ["life", str(path), "--static"])
    assert res.exit_code == 2, res.output
    assert str(path) in res.output and "duty[0]" in res.output and named in res.output
    assert "Traceback" not in res.output


def test_a_steps_other_keys_still_apply(tmp_path):
    """The oil's temperature may differ per step (docs/life.md): kappa of that step follows it by hand."""
    text = PAR_BASE + STEP + 'set = { "lubricant.temperature_C" = 90 }\n'
    b = run_life(tmp_path, text, "--static")["life"]["bearings"][0]
    assert_allclose(b["kappa_points"], [nu_at(90.0, 150.0, 15.0) / nu_1(1000.0, 45.0)], rtol=1e-9)


# --- a zero-load step on the dynamic route ----------------------------------------------------------------------

NOISE_CODES = {"statistics_unresolved", "statistics_undersampled", "window_not_settled", "window_ringing"}


def test_a_zero_load_step_is_at_rest_not_an_unresolved_or_unsettled_window(tmp_path):
    """An idle step (0 N·m) carries F_t of 1e-11 N, round-off: its statistics were judged against that rms and
    warned unresolved (0.54 of 4e-11 N), unsampled, and not settled ("a start-up transient decays through it"),
    and the point was run three times longer looking for a settled window. The unloaded stage's targets now refer to
    at least 1/TARGET times the force the run resolves (e K h^e rtol, h = 1 um: written out below), so the idle
    step is quiet and settled in the file's own window, and its damage is nil as on the static route."""
    steps = (("full", 16200.0, 900.0, 1500.0), ("idle", 3800.0, 0.0, 1500.0))
    doc = run_life(tmp_path, PAR_BASE + duty_text(steps))
    idle = doc["life"]["points"][1]
    assert idle["settled"] is True
    assert idle["solver"]["window_s"] == [0.1, 0.3]  # the file's window: no longer runs
    said = [w for w in doc["warnings"] if "idle" in w["message"] and w["code"] in NOISE_CODES]
    assert said == []
    for member in ("pinion", "gear"):
        for mode in ("pitting", "bending"):
            b = next(b for b in doc["life"]["stages"][0][member][mode]["bins"] if b["point"] == "idle")
            assert b["damage"] == 0.0 and b["force_N"] < 1e-6


def test_the_unloaded_reference_floor_by_hand():
    """estimate.force_floors_N: the line force e K h^e rtol at h = 1 um (an unloaded mesh without backlash: the
    atol's deflection floor), as F_t = F_bt cos(alpha_wt) ... here through the model's own K and e."""
    from gearcli.model import TorsionalModel
    from gearcli.scene import spec_from_design
    from gearcli.simulate.estimate import force_floors_N

    cfg, design = design_of(PAR_BASE, ("load.torque_Nm=0",))
    model = TorsionalModel(spec_from_design(cfg, design))
    (m,) = model.spec.meshes
    line = m.exponent * m.stiffness_N_m_e * 1e-6 ** m.exponent * 1e-6
    # spur, no profile shift: the working pressure angle is 20°, F_t = F_bt cos(20°)
    assert_allclose(force_floors_N(model, 1e-6), [line * math.cos(ALPHA)], rtol=1e-9)
    # far below a loaded mesh's reference (7500 N at 900 N·m) and far above round-off (1e-11 N)
    assert 1e-6 < force_floors_N(model, 1e-6)[0] < 0.1


# --- starts, and hours that are not the required life -------------------------------------------------------------

def test_starts_add_their_own_cycles_and_damage_by_hand(tmp_path):
    """50 starts on the full-load step: each start is the run from rest to the window (the file's 0.05 s speed ramp,
    then full speed), 1500/60 x (t_w - 0.05/2) input revolutions; the pinion turns with the input, the gear 1/3 as
    fast, one tooth contact per turn each. The start's classes are rated on the same S–N curve (written out above)
    and add exactly their own damage."""
    n_starts, hours = 50, 20000.0
    text = PAR_BASE + duty_text((("full", hours, 900.0, 1500.0),)).replace('name = "full"', f'name = "full"\nstarts = {n_starts}')
    life = run_life(tmp_path, text)["life"]
    start = life["points"][0]["start"]
    assert start["count"] == n_starts
    t_w = start["span_s"][1]
    revs = 1500.0 / 60.0 * (t_w - 0.05 / 2.0)  # the ramp's half plus the rest at speed
    assert_allclose(start["input_revolutions"], revs, rtol=1e-9)
    # the ramp's inertia torque on top of the load: the start's peak is above the static 7500 N, by a few per cent
    assert 7500.0 < start["peak_tangential_N"][0] < 1.1 * 7500.0
    for member, speed, nodes in (("pinion", 1.0, ZNT_CASE), ("gear", 1.0 / U, ZNT_CASE)):
        ml = life["stages"][0][member]["pitting"]
        own = [b for b in ml["bins"] if b["point"] == "full (start)"]
        steady = [b for b in ml["bins"] if b["point"] == "full"]
        assert_allclose(sum(b["cycles"] for b in own), n_starts * revs * speed, rtol=1e-9)
        assert_allclose(sum(b["cycles"] for b in steady), hours * 60.0 * 1500.0 * speed, rtol=1e-9)
        d_start = sum(b["cycles"] / cycles_to_failure(b["stress_MPa"] / b["endurance_MPa"], nodes) for b in own)
        assert_allclose(start["damage"][0][member]["pitting"], d_start, rtol=1e-9)
        assert_allclose(ml["damage"], d_start + sum(b["damage"] for b in steady), rtol=1e-9)
    nu = nu_at(70.0, 150.0, 15.0)
    for j, b in enumerate(life["bearings"]):
        speed = 1500.0 if b["shaft"] == 1 else 500.0
        start_revs = n_starts * revs * speed / 1500.0
        assert_allclose(b["revolutions"], hours * 60.0 * speed + start_revs, rtol=1e-12)
        if "kappa" not in b:
            continue
        # the starts are a load level of their own at the bearing's mean speed during a start (revolutions over the
        # start's span): a thinner film than at full speed, so the duty's lowest kappa is the start's
        d_m, cu, kind, c_N = (45.0, 800.0, "ball", 30e3) if b["shaft"] == 1 else (110.0, 9000.0, "roller", 90e3)
        n_start = revs * speed / 1500.0 / (t_w / 60.0)
        assert_allclose(b["kappa"], nu / nu_1(n_start, d_m), rtol=1e-9)
        p_exp = 3.0 if kind == "ball" else 10.0 / 3.0
        e_c = 0.5 if d_m < 100.0 else 0.6
        levels = ((hours * 60.0 * speed, b["loads_N"][0], speed),
                  (start_revs, start["bearings"][j]["equivalent_load_N"], n_start))
        a1 = b["a_1"]
        inverse = sum(r / (a1 * a_iso(nu / nu_1(n, d_m), e_c * cu / p, kind) * (c_N / p) ** p_exp * 1e6)
                      for r, p, n in levels)
        assert_allclose(b["L_nm_Mrev"], sum(r for r, _, _ in levels) / inverse / 1e6, rtol=1e-9)


@pytest.mark.parametrize("second", ["full", "full (start)"])
def test_each_duty_point_has_a_name_of_its_own(tmp_path, second):
    """Two points named "full", each with 100 starts, reported each a start damage of 5.435e-12 (their start
    classes merged by name), the damage of 200 starts: exit 2 naming the second point's name now; so is a point
    named as the first one's start classes. Without starts "full (start)" names no start classes and is a name."""
    def point(name: str, starts: int) -> str:
        return f'\n[[duty]]\nname = "{name}"\nhours = 10000\nstarts = {starts}\ntorque_Nm = 900\nspeed_rpm = 1500\n'

    path = tmp_path / "scene.toml"
    path.write_text(PAR_BASE + point("full", 100) + point(second, 100))
    res = CliRunner().invoke(cli, ["life", str(path), "--static"])
    assert res.exit_code == 2 and str(path) in res.output and "duty[1].name" in res.output, res.output
    assert repr(second) in res.output and "Traceback" not in res.output
    path.write_text(PAR_BASE + point("full", 0) + point(second, 0))
    res = CliRunner().invoke(cli, ["life", str(path), "--static", "-q"])
    assert (res.exit_code == 0) is (second == "full (start)"), res.output
