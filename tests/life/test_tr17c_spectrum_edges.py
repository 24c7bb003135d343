"""``gearcli life --static`` at two edges of a load spectrum, by hand (round-4 trial tr17c).

Scene: one helical stage 22/67, m_n 5, β 15°, x1 0.25, a nitrided pinion on a through-hardened wheel, grade 6, over
a duty whose peak bin lies above the wheel's flank endurance limit and whose other bins lie below it.

- Zero-time bins. A measured spectrum has empty classes (ISO 6336-6:2019 Annex C, Table 4: bins 1, 2 and 45-47
  hold no time), and a user who pastes one gives them ``hours = 0``. Such a bin has no load cycle and no revolution:
  the duty with them is the duty without them, figure for figure, and a ``duty`` note names them. An empty bin with
  starts (which run in its hours) and a duty of empty bins only are exit 2 naming the key.
- Miner elementary and modified have no endurance limit: ISO 6336-6's elementary rule continues the finite-life
  slope k below the knee, so a spectrum entirely below 0.85 σ_∞ still does the damage n/N on that slope, and its
  life is the duty's hours over it. It was printed infinite (``life_h`` null, ``below_endurance``) beside D = 1.23
  and a ``life_safety_low`` warning that the damage reaches 1 within the duty.

Independent of the code: the load cycles (hours × 60 × speed × z1/z2), the wheel's root stress at each bin from
the hand rating of ISO 6336-1/-3 (``tests/reference/rating_hand.py``: every formula typed again) at the bin's torque
and speed with K_A = 1, σ_∞ = σ_FG / Y_NT, the Y_NT nodes of ISO 6336-3:2006 Table 3 for through-hardened steel
(2.5 at 1e4, 1 at 3e6: k = ln 300 / ln 2.5) and Miner's sum.
"""

from __future__ import annotations

import json
import math

from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli
from tests.reference.rating_hand import Member, Pair, rate

Z1, Z2 = 22, 67
REQUIRED_H = 20000.0
SCENE = """
title = "one helical stage over a spectrum (trial tr17c)"
[materials.th]
density_kg_m3 = 7850
youngs_modulus_MPa = 206000
poisson_ratio = 0.3
treatment = "through_hardened"
contact_fatigue_limit_MPa = 750
bending_fatigue_limit_MPa = {flim}
[materials.nt]
density_kg_m3 = 7850
youngs_modulus_MPa = 206000
poisson_ratio = 0.3
treatment = "nitrided"
contact_fatigue_limit_MPa = 1250
bending_fatigue_limit_MPa = 420
[[stage]]
normal_module_mm = 5
normal_pressure_angle_deg = 20
helix_angle_deg = 15
accuracy_grade = 6
pinion = {{ teeth = 22, face_width_mm = 65, hand = "left", material = "nt", profile_shift = 0.25, flank_roughness_Rz_um = 4, root_roughness_Rz_um = 12 }}
gear   = {{ teeth = 67, face_width_mm = 60, hand = "right", material = "th", flank_roughness_Rz_um = 4, root_roughness_Rz_um = 12 }}
[input]
speed_rpm = 1470
[load]
torque_Nm = 3000
[lubricant]
viscosity_40C_mm2_s = 220
[rating]
required_life_h = 20000
min_safety_pitting = 1.0
min_safety_bending = 1.4
"""
# (name, hours, output torque N·m, input speed rpm): 20 000 h in the loaded bins
BINS = [("peak", 400.0, 6500.0, 1470.0), ("nominal", 15000.0, 2000.0, 1470.0), ("slow", 4600.0, 1500.0, 735.0)]
EMPTY = [("top", 0.0, 7200.0, 1470.0), ("idle", 0.0, 300.0, 1470.0)]


def duty(bins) -> str:
    return "".join(f'[[duty]]\nname = "{n}"\nhours = {h}\ntorque_Nm = {t}\nspeed_rpm = {s}\n' for n, h, t, s in bins)


def invoke(tmp_path, text: str, *args: str):
    path = tmp_path / "scene.toml"
    path.write_text(text)
    return CliRunner().invoke(cli, ["-q", "life", str(path), "--static", "--format", "json", *args])


def life_of(tmp_path, text: str, *args: str) -> dict:
    res = invoke(tmp_path, text, *args)
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout)


def hand_pair(flim: float, torque_out_Nm: float, speed_rpm: float) -> Pair:
    """The scene's pair as the hand rating takes it, at one bin (K_A = 1: the spectrum is the load)."""
    return Pair(p=Member(Z1, 65.0, "nitrided", 1250.0, 420.0, 4.0, 12.0, x=0.25),
                g=Member(Z2, 60.0, "through_hardened", 750.0, flim, 4.0, 12.0),
                mn=5.0, alpha_n_deg=20.0, beta_deg=15.0, grade=6, torque_pinion_Nm=torque_out_Nm * Z1 / Z2,
                n1_rpm=speed_rpm, k_a=1.0, nu40=220.0, life_h=REQUIRED_H, s_hmin=1.0, s_fmin=1.4)


def test_zero_time_bins_add_nothing_and_are_named(tmp_path):
    base = SCENE.format(flim=310)
    with_empty = life_of(tmp_path, base + duty([EMPTY[0], *BINS[:2], EMPTY[1], BINS[2]]))
    without = life_of(tmp_path, base + duty(BINS))
    assert with_empty["life"]["stages"] == without["life"]["stages"]
    assert [p["name"] for p in with_empty["life"]["points"]] == [n for n, *_ in BINS]
    assert with_empty["life"]["hours"] == sum(h for _, h, _, _ in BINS) == REQUIRED_H
    notes = [w for w in with_empty["warnings"] if w["code"] == "duty"]
    assert len(notes) == 1 and "top (duty[0])" in notes[0]["message"] and "idle (duty[3])" in notes[0]["message"]
    # the loaded bins' cycles by hand: hours x 60 x the member's speed
    gear = with_empty["life"]["stages"][0]["gear"]["pitting"]["bins"]
    assert_allclose([b["cycles"] for b in gear], [h * 60 * s * Z1 / Z2 for _, h, _, s in BINS], rtol=1e-12)
    # the peak bin is above the wheel's flank endurance limit, the two others below its knee
    ratio = [b["stress_MPa"] / b["endurance_MPa"] for b in gear]
    assert ratio[0] > 1.0 > ratio[1] > ratio[2]


def test_an_empty_bin_with_starts_or_a_duty_of_empty_bins_is_exit_2(tmp_path):
    base = SCENE.format(flim=310)
    res = invoke(tmp_path, base + duty(BINS) + duty([EMPTY[0]]) + "starts = 10\n")
    assert res.exit_code == 2 and "duty[3].hours" in res.output and "Traceback" not in res.output
    res = invoke(tmp_path, base + duty(EMPTY))
    assert res.exit_code == 2 and "duty:" in res.output and "hours = 0" in res.output


def test_miner_elementary_below_the_last_node_has_a_finite_life(tmp_path):
    """σ_Flim 225 puts every bin of the wheel's root under 0.85 σ_∞ (no life under the iso curve's endurance limit),
    yet Miner elementary's slope gives D > 1 over the duty: its life is 20 000 h / D, not infinite."""
    flim = 225.0
    out = life_of(tmp_path, SCENE.format(flim=flim) + duty(BINS), "--miner", "elementary")
    k = math.log(3e6 / 1e4) / math.log(2.5)
    damage = 0.0
    for _, hours, torque, speed in BINS:
        wheel = rate(hand_pair(flim, torque, speed))["gear"]
        sigma_inf = wheel["sigma_FG"] / wheel["Y_NT"]
        assert wheel["sigma_F"] < 0.85 * sigma_inf  # below the iso curve's endurance limit at every bin
        n = hours * 60 * speed * Z1 / Z2
        damage += n / (3e6 * (sigma_inf / wheel["sigma_F"]) ** k)
    assert damage > 1.0
    bending = out["life"]["stages"][0]["gear"]["bending"]
    assert_allclose(bending["damage"], damage, rtol=1e-6)
    assert bending["below_endurance"] is False
    assert_allclose(bending["life_h"], REQUIRED_H / damage, rtol=1e-6)
    verdict = [w for w in out["warnings"] if w["code"] == "life_safety_low" and w["member"] == "gear"
               and w["mode"] == "bending"]
    assert len(verdict) == 1 and verdict[0]["life_h"] == bending["life_h"]
    # the iso variant keeps its endurance limit on the same bins: an infinite life, its extrapolated damage tiny
    iso = life_of(tmp_path, SCENE.format(flim=flim) + duty(BINS))["life"]["stages"][0]["gear"]["bending"]
    assert iso["below_endurance"] is True and iso["life_h"] is None and iso["damage"] < 1e-3 * damage


# the input shaft's two ball bearings, the locating one at x = 0 (the pinion at 60 mm)
BEARINGS = "".join(f'[[bearing]]\nshaft = 1\nposition_mm = {x}\ndynamic_load_rating_kN = 80\nkind = "ball"\n{extra}'
                   for x, extra in ((0, 'locating = true\nfactors = { e = 0.3, X = 0.56, Y = 1.5 }\n'), (300, '')))


def test_a_life_short_of_the_required_life_warns_whatever_the_duty_hours(tmp_path):
    """The same duty as time shares (0.02 + 0.75 + 0.23 = 1 h) against a required 20 000 h: D is over 1 h and far below
    1, the life in hours is the same, and a life shorter than [rating] required_life_h is still a verdict (the wheel's
    flank: 20 000 h / D by hand; the bearing next to the pinion); members and bearings that outlive it are not."""
    base = SCENE.format(flim=310).replace('material = "nt",', 'material = "nt", axial_position_mm = 60,') + BEARINGS
    full = life_of(tmp_path, base + duty(BINS))
    shares = life_of(tmp_path, base + duty([(n, h / REQUIRED_H, t, s) for n, h, t, s in BINS]))
    # the wheel's flank by hand: ISO 6336-2 stresses of each bin (K_A = 1), Z_NT nodes of through-hardened steel
    k_fin, k_long = math.log(5e7 / 1e5) / math.log(1.6), math.log(1e10 / 5e7) / math.log(1 / 0.85)
    damage = 0.0
    for _, hours, torque, speed in BINS:
        wheel = rate(hand_pair(310.0, torque, speed))["gear"]
        sigma_inf = wheel["sigma_HG"] / wheel["Z_NT"]
        y = wheel["sigma_H"] / sigma_inf
        damage += hours * 60 * speed * Z1 / Z2 / (5e7 * (1 / y) ** (k_fin if y >= 1 else k_long))
    life_h = REQUIRED_H / damage
    assert life_h < REQUIRED_H
    for doc in (full, shares):
        flank = doc["life"]["stages"][0]["gear"]["pitting"]
        assert_allclose(flank["life_h"], life_h, rtol=1e-6)
    pitting = shares["life"]["stages"][0]["gear"]["pitting"]
    assert pitting["damage"] < 0.01 and pitting["stress_safety"] > 1.0  # over 1 h: neither verdict of the duty
    verdicts = [(w["member"], w["mode"]) for w in shares["warnings"] if w["code"] == "life_safety_low"]
    assert verdicts == [("gear", "pitting")]
    lives = [b["L10_h"] for b in shares["life"]["bearings"]]
    assert_allclose(lives, [b["L10_h"] for b in full["life"]["bearings"]], rtol=1e-12)
    short = [w["bearing"] for w in shares["warnings"] if w["code"] == "bearing_life_short"
             and "over the duty" in w["message"]]  # the duty's verdict (design's at the base file's load aside)
    assert short == [j + 1 for j, life in enumerate(lives) if life < REQUIRED_H] and len(short) == 1
    assert {w["code"] for w in shares["warnings"]} >= {"duty"}  # the hours' own warning stays
