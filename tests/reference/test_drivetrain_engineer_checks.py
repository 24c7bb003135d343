"""An engineer's own drivetrain scenes (DESIGN §4, §6) against references written out here.

- a 2-DOF linear spur train (speed-driven motor on a coupling, free pinion and gear) forced by a first-harmonic
  transmission error: the steady dynamic mesh force and DTE from the complex 2x2 receptance solved by hand;
- two stages with a flexible intermediate shaft, a load coupling and a drum, forced by a load fluctuation: the
  drum mode from the springs in series (each reflected to the drum by the square of the ratio between) and the
  forced mesh forces from the hand-assembled 4x4 dynamic stiffness;
- an unloaded spur pair with backlash, undamped, behind a prescribed pinion: elastic impacts against a moving
  wall (the gear leaves each drive-flank impact at twice the pinion's line speed and stops at each back-flank
  one), so peak force, penetration, contact-loss and back-flank fractions and the rattle period are closed forms;
- very stiff meshes (the rigid-body limit): window forces equal the static forces 2T/d, speeds the ratio chain;
- a sweep grid over two keys with a value the schema rejects, and a Latin-hypercube tolerance study: every ok
  row equals the one-shot ``gearcli simulate --set`` run of its point, the failed point is a row.
"""

from __future__ import annotations

import csv
import io
import json
import math

import numpy as np
from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli

STEEL = """
[materials.steel]
density_kg_m3 = 7800
youngs_modulus_MPa = 2.07e5
poisson_ratio = 0.29
"""
ALPHA = math.radians(20.0)
RPM = 2 * math.pi / 60


def _invoke(*args: str, code: int = 0) -> str:
    res = CliRunner().invoke(cli, list(args))
    assert res.exit_code == code, res.output
    return res.stdout


def _simulate(tmp_path, text: str, *sets: str, fmt: str = "json"):
    path = tmp_path / "scene.toml"
    path.write_text(text, encoding="utf-8")
    out = _invoke("simulate", str(path), "--format", fmt, "-q", *(a for s in sets for a in ("--set", s)))
    return json.loads(out) if fmt == "json" else list(csv.reader(io.StringIO(out)))


def _rb(m_mm: float, z: int) -> float:
    """Spur base radius z m / 2 cos(alpha), m."""
    return m_mm * z / 2 * math.cos(ALPHA) / 1000


# ----------------------------------------------------------------------------- 2-DOF train, TE harmonic
TE_TRAIN = STEEL + """
[[stage]]
normal_module_mm = 4
normal_pressure_angle_deg = 20
pinion = { teeth = 20, face_width_mm = 30, hand = "spur", material = "steel", inertia_kg_m2 = 0.002 }
gear   = { teeth = 40, face_width_mm = 30, hand = "spur", material = "steel", inertia_kg_m2 = 0.02 }

[contact]
stiffness = 3e5
exponent = 1
damping_ratio = 0.05
transmission_error_um = [5.0]

[input]
speed_rpm = 4500
ramp_s = 0.05
inertia_kg_m2 = 0.01
coupling_stiffness_Nm_rad = 2e4
coupling_damping_Nms_rad = 0.632

[load]
torque_Nm = 750
ramp_s = 0.05

[simulation]
duration_s = 0.3
steps = 30000
"""


def test_two_dof_train_forced_by_a_te_harmonic_against_its_receptance(tmp_path):
    rp, rg = _rb(4, 20), _rb(4, 40)
    Jp, Jg, k, kc, cc = 0.002, 0.02, 3e8, 2e4, 0.632
    m_e = Jp * Jg / (Jp * rg**2 + Jg * rp**2)  # both mesh sides free bodies (the motor is behind the coupling)
    c = 2 * 0.05 * math.sqrt(k * m_e)  # §6: c = 2 zeta sqrt(k_lin m_e)
    w = 20 * 4500 * RPM  # first mesh harmonic; the motor is prescribed: clamped for the vibration
    E = 5e-6
    g = np.array([rp, -rg])  # delta = r_p theta_p - r_g theta_g
    M = np.diag([Jp, Jg])
    K = k * np.outer(g, g) + np.diag([kc, 0.0])
    C = c * np.outer(g, g) + np.diag([cc, 0.0])
    X = np.linalg.solve(-w**2 * M + 1j * w * C + K, (k + 1j * w * c) * E * g)
    q = g @ X - E  # dynamic transmission error amplitude
    force_t = abs((k + 1j * w * c) * q) * math.cos(ALPHA)  # tangential amplitude of the dynamic mesh force
    fn = np.sort(np.sqrt(np.linalg.eigvals(np.linalg.solve(M, K)).real)) / (2 * math.pi)

    d = _simulate(tmp_path, TE_TRAIN)
    s = d["summary"]
    st = s["stages"][0]
    assert_allclose(s["natural_frequencies_Hz"], fn, rtol=1e-9)  # the same linear model
    # window of ~300 mesh periods after the coupling mode (2.6 % damped) has decayed: 1e-3 covers the
    # remaining transient and the phase modulation of e(z_p theta_p) by the pinion's vibration
    assert_allclose(st["dte_um"]["rms"], abs(q) / math.sqrt(2) * 1e6, rtol=1e-3)
    assert_allclose(st["tangential_N"]["std"], force_t / math.sqrt(2), rtol=1e-3)
    # the window's peaks still carry the coupling mode's last run-up ringing (~6 N, within the settle test's
    # 1 % of the static force); the periodic steady state has none
    periodic = _simulate(tmp_path, TE_TRAIN, 'simulation.steady="periodic"')["summary"]["stages"][0]
    assert_allclose(0.5 * (periodic["tangential_N"]["max"] - periodic["tangential_N"]["min"]), force_t, rtol=1e-3)
    assert_allclose(periodic["dte_um"]["rms"], abs(q) / math.sqrt(2) * 1e6, rtol=1e-3)
    static = 750 / rg * math.cos(ALPHA)  # F_t = F_bt cos(alpha) of the load on the gear's base radius
    assert_allclose(st["tangential_N"]["mean"], static, rtol=1e-6)
    assert_allclose(st["dte_um"]["mean"], 750 / rg / k * 1e6, rtol=1e-6)  # static deflection F_bt / k
    assert st["contact_loss_fraction"] == 0.0
    _assert_energy_channels_by_hand(d["energy"], rp, rg, k, kc)


def _assert_energy_channels_by_hand(energy: dict, rp: float, rg: float, k: float, kc: float) -> None:
    """The 2-DOF train's energy over its 0.3 s run: the bodies' kinetic energy at their final speeds (the motor's
    too: its prescribed motion is paid by the input work), the coupling's twist and the mesh's deflection under
    the static load, and the load's work T_L(t) w_g(t) with both STEP ramps ending at T = 0.05 s."""
    Om, T, TL, i = 4500 * RPM, 0.05, 750.0, rg / rp
    kinetic = 0.5 * (0.01 + 0.002) * Om**2 + 0.5 * 0.02 * (Om / i) ** 2
    twist, deflection = TL / i / kc, TL / rg / k  # coupling twist (pinion torque / kc), mesh F_bt / k
    potential = 0.5 * kc * twist**2 + 0.5 * k * deflection**2
    # int_0^T STEP_T * STEP_w dt = T int_0^1 (s^2 (3 - 2 s))^2 ds = T (9/5 - 2 + 4/7); the gear lags the rigid
    # motion by its compliance in proportion to the load: int T_L d(lag) = T_L lag / 2 at the end
    lag = twist / i + deflection / rg
    load = TL * Om / i * (0.3 - T + T * (9 / 5 - 2 + 4 / 7)) - 0.5 * TL * lag
    assert_allclose(energy["kinetic_change_J"], kinetic, rtol=1e-4)  # + the TE's vibration at the end (~1e-5)
    assert_allclose(energy["potential_change_J"], potential, rtol=2e-2)  # + the vibration's own share (~0.7 %)
    assert_allclose(energy["load_work_J"], load, rtol=1e-4)  # the inertial lag of the ramp: ~3e-5
    assert energy["damping_loss_J"] > 0.0
    assert_allclose(energy["input_work_J"], energy["load_work_J"] + energy["damping_loss_J"]
                    + energy["kinetic_change_J"] + energy["potential_change_J"], rtol=1e-8)


# ------------------------------------------------------------ springs in series, load fluctuation
SERIES = STEEL + """
[[stage]]
normal_module_mm = 3
normal_pressure_angle_deg = 20
pinion = { teeth = 20, face_width_mm = 30, hand = "spur", material = "steel", inertia_kg_m2 = 0.001 }
gear   = { teeth = 60, face_width_mm = 30, hand = "spur", material = "steel", inertia_kg_m2 = 0.005 }
[stage.shaft]
stiffness_Nm_rad = 2e5
damping_Nms_rad = 5.0

[[stage]]
normal_module_mm = 5
normal_pressure_angle_deg = 20
pinion = { teeth = 18, face_width_mm = 50, hand = "spur", material = "steel", inertia_kg_m2 = 0.002 }
gear   = { teeth = 54, face_width_mm = 50, hand = "spur", material = "steel", inertia_kg_m2 = 0.02 }

[contact]
stiffness = 1e6
exponent = 1
damping_ratio = 0.05

[input]
speed_rpm = 1500
ramp_s = 0.2

[load]
torque_Nm = 2000
ramp_s = 0.2
inertia_kg_m2 = 5
coupling_stiffness_Nm_rad = 5e4
coupling_damping_Nms_rad = 300
fluctuation = [{amplitude_percent = 10, frequency_Hz = 5}]

[simulation]
duration_s = 1.5
steps = 30000
steady = "periodic"
"""


def test_drum_mode_from_springs_in_series_and_the_forced_response_to_a_load_fluctuation(tmp_path):
    r1g, r2p, r2g = _rb(3, 60), _rb(5, 18), _rb(5, 54)
    Jg1, Jp2, Jg2, Jd = 0.005, 0.002, 0.02, 5.0
    k1 = k2 = 1e9
    ks, cs, kc, cc = 2e5, 5.0, 5e4, 300.0
    i2 = 54 / 18
    # the drum on the chain coupling - mesh 2 - shaft - mesh 1 (pinion 1 prescribed, held for the vibration);
    # a spring nearer the input is seen from the drum stiffer by the square of the ratio between them
    k_series = 1 / (1 / kc + 1 / (k2 * r2g**2) + 1 / (ks * i2**2) + 1 / (k1 * r1g**2 * i2**2))
    f_series = math.sqrt(k_series / Jd) / (2 * math.pi)
    # the exact 4-DOF chain (gear 1, pinion 2, gear 2, drum), assembled by hand
    M = np.diag([Jg1, Jp2, Jg2, Jd])
    g1, g2 = np.array([-r1g, 0, 0, 0]), np.array([0, r2p, -r2g, 0])
    sh, cp = np.array([1, -1, 0, 0]), np.array([0, 0, 1, -1])
    c1 = 2 * 0.05 * math.sqrt(k1 * Jg1 / r1g**2)  # m_e of a mesh behind a prescribed pinion: J_g / r_g^2
    c2 = 2 * 0.05 * math.sqrt(k2 * Jp2 * Jg2 / (Jp2 * r2g**2 + Jg2 * r2p**2))
    K = k1 * np.outer(g1, g1) + k2 * np.outer(g2, g2) + ks * np.outer(sh, sh) + kc * np.outer(cp, cp)
    C = c1 * np.outer(g1, g1) + c2 * np.outer(g2, g2) + cs * np.outer(sh, sh) + cc * np.outer(cp, cp)
    fn = np.sort(np.sqrt(np.linalg.eigvals(np.linalg.solve(M, K)).real)) / (2 * math.pi)
    w = 2 * math.pi * 5.0
    X = np.linalg.solve(-w**2 * M + 1j * w * C + K, np.array([0, 0, 0, -0.1 * 2000]))  # T_L a sin(wt) on the drum
    std1 = abs((k1 + 1j * w * c1) * (g1 @ X)) * math.cos(ALPHA) / math.sqrt(2)
    std2 = abs((k2 + 1j * w * c2) * (g2 @ X)) * math.cos(ALPHA) / math.sqrt(2)

    s = _simulate(tmp_path, SERIES)["summary"]
    assert_allclose(s["natural_frequencies_Hz"], fn, rtol=1e-9)
    assert_allclose(s["natural_frequencies_Hz"][0], f_series, rtol=1e-3)  # the gears' own inertia: ~2e-5
    assert s["steady"]["converged"] and s["steady"]["period_s"] == 0.2
    st1, st2 = s["stages"]
    assert_allclose(st1["tangential_N"]["std"], std1, rtol=1e-4)  # whole periods of the periodic state
    assert_allclose(st2["tangential_N"]["std"], std2, rtol=1e-4)
    assert_allclose(st2["tangential_N"]["mean"], 2000 / r2g * math.cos(ALPHA), rtol=1e-6)
    assert_allclose(st1["tangential_N"]["mean"], 2000 / i2 / r1g * math.cos(ALPHA), rtol=1e-6)


# ------------------------------------------------------------------------------- unloaded rattle
RATTLE = STEEL + """
[[stage]]
normal_module_mm = 3
normal_pressure_angle_deg = 20
backlash_mm = 0.1
pinion = { teeth = 25, face_width_mm = 20, hand = "spur", material = "steel" }
gear   = { teeth = 25, face_width_mm = 20, hand = "spur", material = "steel", inertia_kg_m2 = 0.0063 }

[contact]
stiffness = 2e5
exponent = 1
damping_ratio = 0.0

[input]
speed_rpm = 60
ramp_s = 1e-5

[load]
torque_Nm = 0
ramp_s = 0

[simulation]
duration_s = 0.05
steps = 50000
"""


def test_unloaded_rattle_is_a_train_of_elastic_impacts(tmp_path):
    rb = _rb(3, 25)
    V = rb * 60 * RPM  # the pinion's line speed (reached within the 10 us ramp, long before the first contact)
    m_e = 0.0063 / rb**2  # prescribed pinion: m_e = J_g / r_bg^2
    k, j = 2e8, 1e-4
    # a linear elastic contact against a wall moving at V reverses the relative speed: the gear leaves each
    # drive-flank impact at 2V, crosses the whole gap j at relative speed V, and the back flank stops it again
    t_contact = math.pi * math.sqrt(m_e / k)  # half a period of the contact oscillator
    t_gap = j / V
    peak_n = V * math.sqrt(k * m_e)  # energy: m_e V^2 / 2 = k p^2 / 2
    rows = _simulate(tmp_path, RATTLE, fmt="csv")
    head, data = rows[0], np.array(rows[1:], dtype=float)
    t, w_gear = data[:, 0], data[:, head.index("shaft2_speed_rpm")]
    up = np.nonzero((w_gear[:-1] < 60) & (w_gear[1:] >= 60))[0]
    assert_allclose(np.diff(t[up])[-5:], 2 * (t_gap + t_contact), atol=2e-6)  # the output step is 1 us
    late = t > 0.01
    assert_allclose([w_gear[late].min(), w_gear[late].max()], [0.0, 120.0], atol=0.02)

    d = _simulate(tmp_path, RATTLE)
    st = d["summary"]["stages"][0]
    # at the default rtol, the product's target: the extremes within 1e-3 of the stage's reference force (its rms,
    # 3398 N) of the closed form. What is left is the step pattern's error through ~50 impacts, of either sign and
    # converging with rtol, no bias: DOP853 step ceilings of 5.8..6.03 / max|lambda| (eight radii) left the peak
    # -8.9e-5..+2.6e-4 of it off (1.7 N at most, half the target), 2.2e-5 at most at rtol 1e-7, 2.2e-6 at 1e-8
    target_N = st["error_estimate"]["target_relative"] * st["error_estimate"]["reference_N"]
    assert abs(st["tangential_N"]["max"] - peak_n * math.cos(ALPHA)) <= target_N
    assert abs(st["tangential_N"]["min"] + peak_n * math.cos(ALPHA)) <= target_N
    # the closed forms themselves, tightly, where the solver's share is small (rtol 1e-8)
    tight = _simulate(tmp_path, RATTLE, "simulation.rtol=1e-8")["summary"]["stages"][0]
    assert_allclose(tight["tangential_N"]["max"], peak_n * math.cos(ALPHA), rtol=1e-5)
    assert_allclose(tight["tangential_N"]["min"], -peak_n * math.cos(ALPHA), rtol=1e-5)
    assert_allclose(tight["penetration_mm"]["max"], V * math.sqrt(m_e / k) * 1e3, rtol=1e-5)
    assert_allclose(tight["dte_um"]["max"], (j / 2 + V * math.sqrt(m_e / k)) * 1e6, rtol=1e-5)  # gap included
    # fractions of a window of ~21 cycles, not whole ones: one cycle's share of error at most
    cycle = t_gap + t_contact
    assert_allclose(st["contact_loss_fraction"], t_gap / cycle, atol=2e-3)
    assert_allclose(st["back_flank_fraction"], t_contact / (2 * cycle), atol=2e-3)
    assert st["regime"] == "double-sided impact"
    assert d["energy"]["damping_loss_J"] == 0.0 and d["energy"]["load_work_J"] == 0.0
    # nothing is lost: the input work is the gear's kinetic plus the mesh's elastic energy at the end
    assert_allclose(d["energy"]["input_work_J"],
                    d["energy"]["kinetic_change_J"] + d["energy"]["potential_change_J"], rtol=1e-3)
    assert d["energy"]["input_work_J"] <= 0.5 * 0.0063 * (2 * 60 * RPM) ** 2 * (1 + 1e-6)


def test_an_unloaded_mesh_ringing_is_measured_against_its_window_not_a_static_force(tmp_path):
    # without backlash and damping the unloaded gear swings through both flanks for ever; the mesh carries
    # no static force, so the warning's reference is the window's mean |F_t| (2/pi of the swing's amplitude),
    # and it must not call that "the static" force
    d = _simulate(tmp_path, RATTLE, "stage.0.backlash_mm=0")
    ringing = [w for w in d["warnings"] if w["code"] == "window_ringing"]
    assert ringing, d["warnings"]
    amplitude = _rb(3, 25) * 60 * RPM * math.sqrt(2e8 * 0.0063 / _rb(3, 25) ** 2) * math.cos(ALPHA)
    assert_allclose(ringing[0]["reference_N"], 2 / math.pi * amplitude, rtol=2e-3)
    assert "the static" not in ringing[0]["message"]
    assert "no static load" in ringing[0]["message"]
    assert d["summary"]["stages"][0]["static_tangential_N"] == 0.0


# ------------------------------------------------------------------------------- rigid-body limit
RIGID = STEEL + """
[[stage]]
normal_module_mm = 4
normal_pressure_angle_deg = 20
helix_angle_deg = 15
pinion = { teeth = 19, face_width_mm = 45, hand = "left", material = "steel" }
gear   = { teeth = 77, face_width_mm = 40, hand = "right", material = "steel" }

[[stage]]
normal_module_mm = 6
normal_pressure_angle_deg = 22.5
helix_angle_deg = 10
pinion = { teeth = 17, face_width_mm = 70, hand = "right", material = "steel" }
gear   = { teeth = 62, face_width_mm = 65, hand = "left", material = "steel" }

[contact]
stiffness = 1e8
exponent = 1

[input]
speed_rpm = 1480
ramp_s = 0.3

[load]
torque_Nm = 3500
ramp_s = 0.3

[simulation]
duration_s = 0.6
steps = 600
"""


def _static(torque_Nm: float, m_n: float, alpha_n_deg: float, beta_deg: float, z_gear: int) -> tuple:
    """(F_t, F_r, F_a) of a torque on a gear: F_t = 2T/d, d = z m_n / cos(beta), F_r = F_t tan(alpha_t)."""
    beta = math.radians(beta_deg)
    alpha_t = math.atan(math.tan(math.radians(alpha_n_deg)) / math.cos(beta))
    ft = torque_Nm / (z_gear * m_n / math.cos(beta) / 2000)
    return ft, ft * math.tan(alpha_t), ft * math.tan(beta)


def test_very_stiff_meshes_give_the_static_forces_and_the_ratio_chain(tmp_path):
    d = _simulate(tmp_path, RIGID)
    s = d["summary"]
    i = 77 / 19 * 62 / 17
    expected = (_static(3500 * 17 / 62, 4, 20, 15, 77), _static(3500, 6, 22.5, 10, 62))
    for st, (ft, fr, fa) in zip(s["stages"], expected, strict=True):
        assert_allclose([st["tangential_N"]["mean"], st["radial_N"]["mean"], st["axial_N"]["mean"]],
                        [ft, fr, fa], rtol=1e-9)  # 1e8 N/mm meshes, settled: no dynamic part left
        assert st["tangential_N"]["std"] < 1e-9 * ft
    assert_allclose(s["ratio"], i, rtol=1e-12)
    assert_allclose(s["output_speed_rpm"], 1480 / i, rtol=1e-12)
    assert_allclose(s["input_torque_Nm"], 3500 / i, rtol=1e-9)  # a lossless train: T_in = T_L / i


# ------------------------------------------------------------------------------------- sweeps
SHORT = TE_TRAIN.replace("duration_s = 0.3", "duration_s = 0.15").replace("steps = 30000", "steps = 15000")
COMPARED = ("tangential_N", "mean", "std", "min", "max"), ("dte_um", "mean", "rms", "min", "max")


def _sweep_rows(tmp_path, *args: str) -> tuple[list[dict], str]:
    path = tmp_path / "scene.toml"
    path.write_text(SHORT, encoding="utf-8")
    out = tmp_path / "rows.csv"
    res = CliRunner().invoke(cli, ["sweep", str(path), "--jobs", "1", "-q", "-o", str(out), *args])
    with out.open(encoding="utf-8") as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#"))), str(res.exit_code)


def _assert_row_is_the_one_shot(tmp_path, row: dict, sets: list[str]) -> None:
    d = _simulate(tmp_path, SHORT, *sets)
    st = d["summary"]["stages"][0]
    for channel, *stats in COMPARED:
        for q in stats:
            assert_allclose(float(row[f"stage1_{channel}_{q}"]), st[channel][q], rtol=1e-12, err_msg=f"{channel} {q}")
    assert_allclose(float(row["stage1_contact_loss_fraction"]), st["contact_loss_fraction"], atol=0)
    assert_allclose(float(row["stage1_dynamic_factor"]), st["dynamic_factor"], rtol=1e-12)
    assert_allclose(float(row["output_speed_rpm"]), d["summary"]["output_speed_rpm"], rtol=1e-12)


def test_a_two_key_grid_matches_one_shot_runs_and_keeps_going_past_a_rejected_value(tmp_path):
    rows, code = _sweep_rows(tmp_path, "--vary", "input.speed_rpm=3000,4500", "--vary", "contact.damping_ratio=0.05,-1")
    assert code == "1"  # a failed point: exit 1, the sweep complete
    assert [(r["input.speed_rpm"], r["contact.damping_ratio"], r["status"]) for r in rows] == [
        ("3000", "0.05", "ok"), ("3000", "-1", "failed"), ("4500", "0.05", "ok"), ("4500", "-1", "failed")]
    for r in rows:
        assert r["direction"] == "none"
        if r["status"] == "failed":
            assert r["message"].startswith("contact.damping_ratio: must be ≥ 0")
            assert r["stage1_tangential_N_mean"] == ""
        else:
            _assert_row_is_the_one_shot(tmp_path, r, [f"input.speed_rpm={r['input.speed_rpm']}",
                                                      f"contact.damping_ratio={r['contact.damping_ratio']}"])


def test_a_tolerance_study_draws_one_sample_per_stratum_and_its_rows_match_one_shot_runs(tmp_path):
    n = 3
    rows, code = _sweep_rows(tmp_path, "--samples", str(n), "--seed", "3",
                             "--random", "contact.transmission_error_um.0=normal(5,1)",
                             "--random", "load.torque_Nm=uniform(500,900)")
    assert code == "0" and len(rows) == n
    from scipy.stats import norm
    te = np.array([float(r["contact.transmission_error_um.0"]) for r in rows])
    torque = np.array([float(r["load.torque_Nm"]) for r in rows])
    # a Latin hypercube: each of the n equal-probability strata of each key holds exactly one draw
    assert sorted(np.floor(norm.cdf(te, 5, 1) * n).astype(int)) == list(range(n))
    assert sorted(np.floor((torque - 500) / 400 * n).astype(int)) == list(range(n))
    for r in rows:
        _assert_row_is_the_one_shot(tmp_path, r, [f"contact.transmission_error_um.0={r['contact.transmission_error_um.0']}",
                                                  f"load.torque_Nm={r['load.torque_Nm']}"])


# --------------------------------------------------------- unloaded statistics: the targets' reference
def test_an_unloaded_mesh_statistics_refer_to_its_rms_not_to_a_mean_that_is_noise():
    from gearcli.simulate.estimate import stage_error

    # by hand: an unloaded mesh swinging ±75 N at 1 kHz about a mean that is zero but for 1e-4 N of noise; the
    # check pass differs by 1e-3 N everywhere. Against the noise (1e-4 N) that error is 10x "the mean"; against
    # what the mesh carries, its rms 75/sqrt(2) N, it is 2e-5: resolved
    t = np.linspace(0.0, 0.1, 20001)
    run = 75.0 * np.sin(2 * np.pi * 1000.0 * t) + 1e-4
    e = stage_error(0, t, run, run + 1e-3, 0.0, 1e-6)
    assert_allclose(e.reference_N, 75.0 / math.sqrt(2), rtol=1e-4)
    assert_allclose(e.tangential_N.mean, 1e-3, rtol=1e-6)
    assert e.resolved and e.suggested_rtol is None
    loaded = stage_error(0, t, run + 1000.0, run + 1000.0 + 1e-3, 1000.0, 1e-6)  # a loaded mesh: |mean| as before
    assert_allclose(loaded.reference_N, 1000.0 + 1e-4, rtol=1e-12)


def test_an_unloaded_rattling_train_is_not_warned_unresolved_against_its_zero_mean(tmp_path):
    # the 2-DOF train without load and with 0.05 mm backlash: TE drives the gear across the gap, F_t swings ±75 N
    # about a window mean of ~1e-4 N; the statistics are resolved to 1e-3 of that swing at the file's rtol
    d = _simulate(tmp_path, SHORT, "load.torque_Nm=0", "stage.0.backlash_mm=0.05")
    st = d["summary"]["stages"][0]
    ft = st["tangential_N"]
    assert abs(ft["mean"]) < 1e-3 * ft["std"]
    assert_allclose(st["error_estimate"]["reference_N"], math.hypot(ft["mean"], ft["std"]), rtol=1e-6)
    assert_allclose(st["sampling_error"]["reference_N"], math.hypot(ft["mean"], ft["std"]), rtol=1e-6)
    assert not [w for w in d["warnings"] if w["code"] in ("statistics_unresolved", "statistics_undersampled")]
    assert st["error_estimate"]["resolved"] and st["sampling_error"]["resolved"]


# ------------------------------------------------------------------ time-varying helical mesh stiffness
TIME_VARYING = STEEL + """
[[stage]]
normal_module_mm = 4
normal_pressure_angle_deg = 20
helix_angle_deg = 15
pinion = { teeth = 19, face_width_mm = 45, hand = "left", material = "steel", inertia_kg_m2 = 0.001 }
gear   = { teeth = 77, face_width_mm = 45, hand = "right", material = "steel", inertia_kg_m2 = 0.05 }

[contact]
stiffness = 5e5
exponent = 1
damping_ratio = 0.3
time_varying = true

[input]
speed_rpm = 10
ramp_s = 0.05

[load]
torque_Nm = 1000
ramp_s = 0.05

[simulation]
duration_s = 0.6
steps = 12000
window_start_s = 0.2
rtol = 1e-8
"""


def _contact_points_share(phi: np.ndarray, eps_alpha: float, eps_beta: float, n_face: int = 4001) -> np.ndarray:
    """L(phi) / L_mean by counting: across the face (y from 0 to 1 of b) the line whose foot is at phi + j (in base
    pitches along the path of contact) meets the path at phi + j + eps_beta y; the contact-line length is the
    face-averaged number of those points on the path [0, eps_alpha] (times b / cos(beta_b)), its mean eps_alpha."""
    y = np.linspace(0.0, 1.0, n_face)
    x = np.asarray(phi, float)[:, None] % 1.0
    count = np.zeros(x.shape[0])
    for j in range(-int(eps_beta) - 2, int(eps_alpha) + 3):
        p = x + j + eps_beta * y
        count += np.mean((p >= 0.0) & (p <= eps_alpha), axis=1)
    return count / eps_alpha


def test_a_slow_helical_mesh_follows_its_contact_line_length(tmp_path):
    # 10 rpm: the mesh frequency (3.2 Hz) is 1e-3 of the mesh mode (2.3 kHz), so the gear follows quasi-statically:
    # the mesh carries the static F_bt at every phase and deflects q = F_bt / (k_t L/L_mean), k_t = K cos^2(beta_b)
    path = tmp_path / "scene.toml"
    path.write_text(TIME_VARYING, encoding="utf-8")
    design = json.loads(_invoke("design", str(path), "--format", "json", "-q"))["stages"][0]
    ea, eb = design["contact_ratio_transverse"], design["overlap_ratio"]
    rows = _simulate(tmp_path, TIME_VARYING, fmt="csv")
    head, data = rows[0], np.array(rows[1:], dtype=float)
    t, q = data[:, 0], data[:, head.index("stage1_dte_um")]
    pick = np.nonzero(t >= 0.2)[0][::20]  # 1.3 mesh cycles: both plateaus and the ramps between
    beta = math.radians(15.0)
    alpha_t = math.atan(math.tan(ALPHA) / math.cos(beta))
    beta_b = math.atan(math.tan(beta) * math.cos(alpha_t))
    rbg = 4 * 77 / math.cos(beta) / 2 * math.cos(alpha_t) / 1000
    omega = 10 * RPM
    phi = 19 * omega * (t[pick] - 0.05 / 2) / (2 * math.pi)  # after the STEP ramp the angle lags by w T / 2
    expected = 1000 / rbg / (5e8 * math.cos(beta_b) ** 2 * _contact_points_share(phi, ea, eb)) * 1e6
    # the face grid (4001 points) resolves L to ~1e-4; the gear's inertia and damping at 1e-3 of resonance ~1e-5
    assert_allclose(q[pick], expected, rtol=3e-4)
    share = _contact_points_share(np.linspace(0, 1, 2001), ea, eb)
    assert share.max() / share.min() > 1.04  # eps_beta = 0.93: a 5 % stiffness variation, visible in q
    ft = _simulate(tmp_path, TIME_VARYING)["summary"]["stages"][0]["tangential_N"]
    assert_allclose([ft["min"], ft["max"]], [2000 / (4 * 77 / math.cos(beta) / 1000)] * 2, rtol=2e-4)


def test_a_continuation_file_with_rows_missing_inside_its_branches_resumes_to_the_uninterrupted_file(tmp_path):
    # a resumed branch recomputes the points before a missing one for their state, writes only the missing rows,
    # and the completed file equals the uninterrupted one but for wall_s (docs/sweeps.md, "-o FILE")
    args = ("--vary", "input.speed_rpm=3000:4500:3", "--direction", "both")
    full, code = _sweep_rows(tmp_path, *args)
    assert code == "0" and [r["direction"] for r in full] == ["up"] * 3 + ["down"] * 3
    out = tmp_path / "rows.csv"
    lines = out.read_text(encoding="utf-8").splitlines(keepends=True)
    out.write_text("".join(lines[:2] + [lines[2], lines[4], lines[6]]), encoding="utf-8")  # 2nd of up, 1st and 3rd of down gone
    resumed, code = _sweep_rows(tmp_path, *args)
    assert code == "0"
    strip = [{k: v for k, v in r.items() if k != "wall_s"} for r in full]
    assert [{k: v for k, v in r.items() if k != "wall_s"} for r in resumed] == strip
