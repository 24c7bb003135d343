"""`gearcli report` on an engineer's own scenes (trial, round 5, rep2), checked against hand calculations.

Spur stage, linear mesh (exponent 1, K = 4e5 N/mm, no backlash, no excitation), 21/63 teeth, m = 4 mm, α = 20°,
1500 rpm against 600 N·m on the gear. By hand:
  d_1 = m z_1 = 84 mm, i = 63 / 21 = 3, output 1500 / 3 = 500 rpm, pinion torque 600 / 3 = 200 N·m,
  F_t = 2 T_1 / d_1 = 2 · 200e3 / 84 = 4761.905 N, F_r = F_t tan 20° = 1733.19 N, F_a = 0,
  mesh frequency z_1 n_1 / 60 = 21 · 1500 / 60 = 525 Hz,
  ε_α = (√(r_a1² − r_b1²) + √(r_a2² − r_b2²) − a sin α) / (π m cos α) = 1.6807.
In the rigid limit (settled, no excitation) the window means are the static values to the solver's accuracy.

Lossy three-stage helical reducer (η = 0.98, 0.97, 0.96), 9000 N·m on the output. Forward load: the pinion drives,
T_p = T_g / (i η) down the train. Reversed (overhauling, −9000 N·m): the gear drives, its tooth force is
T_g / r_g (T_g the gear's own torque, T_p = T_g η / i up the train), which the simulation's window mean equals; the
report's theory column showed the design's pinion-side force η T_g / r_g instead, a 1/η − 1 = 2.0, 3.1 and 4.2 %
"error" in the rigid limit.
"""

from __future__ import annotations

import json
import math

import pytest
from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli

SPUR = """
title = "Single spur stage, linear mesh"
[[stage]]
normal_module_mm = 4
normal_pressure_angle_deg = 20
helix_angle_deg = 0
pinion = { teeth = 21, face_width_mm = 40, material = "steel" }
gear   = { teeth = 63, face_width_mm = 40, material = "steel" }
[contact]
stiffness = 4e5
exponent = 1
damping_Ns_mm = 5
full_damping_penetration_mm = 0.001
[input]
speed_rpm = 1500
ramp_s = 0.1
[load]
torque_Nm = 600
ramp_s = 0.1
[simulation]
duration_s = 0.4
steps = 2000
"""

LOSSY3 = """
title = "Lossy three-stage helical reducer"
[[stage]]
normal_module_mm = 2.5
normal_pressure_angle_deg = 20
helix_angle_deg = 15
efficiency = 0.98
pinion = { teeth = 20, face_width_mm = 35, hand = "left", material = "steel" }
gear   = { teeth = 71, face_width_mm = 32, hand = "right", material = "steel" }
[[stage]]
normal_module_mm = 4
normal_pressure_angle_deg = 20
helix_angle_deg = 12
efficiency = 0.97
pinion = { teeth = 19, face_width_mm = 55, hand = "right", material = "steel" }
gear   = { teeth = 67, face_width_mm = 50, hand = "left", material = "steel" }
[[stage]]
normal_module_mm = 6
normal_pressure_angle_deg = 20
helix_angle_deg = 10
efficiency = 0.96
pinion = { teeth = 17, face_width_mm = 90, hand = "left", material = "steel" }
gear   = { teeth = 59, face_width_mm = 85, hand = "right", material = "steel" }
[contact]
stiffness = "iso6336"
exponent = 1.5
damping_ratio = 0.05
[input]
speed_rpm = 1480
ramp_s = 0.15
[load]
torque_Nm = LOAD
ramp_s = 0.15
[simulation]
duration_s = 0.5
"""
STAGES = ((2.5, 15.0, 20, 71, 0.98), (4.0, 12.0, 19, 67, 0.97), (6.0, 10.0, 17, 59, 0.96))  # m_n, β, z1, z2, η


def _run(*args: str) -> tuple[int, str]:
    res = CliRunner().invoke(cli, [*args, "-q"])
    return res.exit_code, res.stdout


def _forces_by_hand(load_Nm: float) -> list[tuple[float, float, float]]:
    """(F_t, F_r, F_a) per stage, signed with the load, of the member that drives: the pinion's F_t = 2 T_p / d_p
    with T_p = T_g / (i η) for a forward load; the gear's F_t = 2 T_g / d_g for a reversed one."""
    out = []
    torque = load_Nm * 1e3  # N·mm on the last gear
    for m_n, beta_deg, z1, z2, eta in reversed(STAGES):
        beta = math.radians(beta_deg)
        d1, d2 = m_n * z1 / math.cos(beta), m_n * z2 / math.cos(beta)
        alpha_t = math.atan(math.tan(math.radians(20.0)) / math.cos(beta))
        ratio = z2 / z1
        f_t = 2 * torque / d2 if torque < 0 else 2 * torque / (ratio * eta) / d1
        out.append((f_t, f_t * math.tan(alpha_t), f_t * math.tan(beta)))
        torque = torque * eta / ratio if torque < 0 else torque / (ratio * eta)  # the next pinion's = this gear's
    return out[::-1]


@pytest.fixture(scope="module")
def spur(tmp_path_factory):
    path = tmp_path_factory.mktemp("spur") / "spur.toml"
    path.write_text(SPUR)
    out = {"path": path}
    for fmt in ("json", "markdown"):
        code, out[fmt] = _run("report", str(path), "--quick", "--format", fmt)
        assert code == 0
    for cmd in ("design", "simulate"):
        code, text = _run(cmd, str(path), "--format", "json")
        assert code == 0
        out[cmd] = json.loads(text)
    out["report"] = json.loads(out["json"])
    return out


def test_spur_theory_column_by_hand(spur):
    theory = {(c["stage"], c["quantity"]): c["theory"] for c in spur["report"]["comparison"]}
    f_t = 2 * 200e3 / 84.0
    assert_allclose(theory[(None, "ratio")], 3.0, rtol=1e-14)
    assert_allclose(theory[(None, "output_speed_deg_s")], 500 * 6.0, rtol=1e-14)  # 500 rpm = 3000 °/s
    assert_allclose(theory[(1, "tangential_N")], f_t, rtol=1e-12)
    assert_allclose(theory[(1, "radial_N")], f_t * math.tan(math.radians(20)), rtol=1e-12)
    assert theory[(1, "axial_N")] == 0.0
    stage = spur["report"]["design"]["stages"][0]
    assert_allclose(stage["mesh_frequency_Hz"], 525.0, rtol=1e-12)
    r_a1, r_b1, r_a2, r_b2 = 46.0, 42 * math.cos(math.radians(20)), 130.0, 126 * math.cos(math.radians(20))
    eps = (math.sqrt(r_a1**2 - r_b1**2) + math.sqrt(r_a2**2 - r_b2**2) - 168 * math.sin(math.radians(20))) / (
        math.pi * 4 * math.cos(math.radians(20)))
    assert_allclose(stage["contact_ratio_transverse"], eps, rtol=1e-9)


def test_spur_rigid_limit_simulation_meets_theory(spur):
    """Linear mesh, settled, nothing excites it: the window means are the statics to the solver's rtol (1e-6
    here; the linear mesh's mean is far better, the test allows 1e-7)."""
    for row in spur["report"]["comparison"]:
        if row["theory"] != 0:
            assert abs(row["error_percent"]) < 1e-5, row  # 1e-7 relative
    dyn = spur["report"]["dynamics"][0]
    assert_allclose(dyn["dynamic_factor"], 1.0, atol=1e-6)  # no fluctuation in the window


def test_spur_report_numbers_equal_design_and_simulate(spur):
    """The same file: the report's design is `design`'s JSON, its simulation summary's stage statistics are
    `simulate`'s, to the last digit (the same deterministic run)."""
    rep, des, sim = spur["report"], spur["design"], spur["simulate"]
    for key in ("total_ratio", "output_speed_rpm", "input_torque_Nm", "output_torque_Nm"):
        assert rep["design"][key] == des[key], key
    # the markdown's design section prints m_n, β, a, b, c_γα and the teeth: the JSON carries them too (they were
    # missing), under design's own key names
    for key in ("static_force_N", "mesh_frequency_Hz", "contact_ratio_transverse", "iso6336_mesh_stiffness_N_mm_um",
                "normal_module_mm", "helix_angle_deg", "center_distance_mm", "face_width_mm"):
        assert rep["design"]["stages"][0][key] == des["stages"][0][key], key
    for member in ("pinion", "gear"):
        assert rep["design"]["stages"][0][member]["teeth"] == des["stages"][0][member]["teeth"]
    assert_allclose(rep["design"]["stages"][0]["center_distance_mm"], 4 * (21 + 63) / 2, rtol=1e-12)
    r_st, s_st = rep["dynamics"][0], sim["summary"]["stages"][0]
    for key in ("tangential_N", "radial_N", "axial_N", "dynamic_factor", "runup_factor", "peak_tangential_N",
                "static_tangential_N", "simulated_static_tangential_N"):
        assert r_st[key] == s_st[key], key
    assert rep["simulation"]["summary"]["output_speed_deg_s"] == sim["summary"]["output_speed_deg_s"]
    assert rep["natural_frequencies_Hz"] == sim["summary"]["natural_frequencies_Hz"]
    assert [w["code"] for w in rep["warnings"]] == [w["code"] for w in sim["warnings"]]


def test_spur_markdown_rows_are_the_json_numbers(spur):
    """The markdown's theory-against-simulation rows print the JSON's numbers (speeds in the file's rpm)."""
    md = spur["markdown"].split("## Theory against simulation", 1)[1].split("\n## ", 1)[0]
    rows = [[c.strip() for c in x.strip().strip("|").split("|")] for x in md.splitlines() if x.startswith("| ")]
    assert rows[0] == ["stage", "quantity", "theory (static)", "simulated (mean)", "error [%]"]
    cells = {(r[0], r[1]): r for r in rows[2:]}
    assert_allclose(float(cells[("1", "F_t mean [N]")][2]), 2 * 200e3 / 84.0, rtol=5e-6)  # 6 digits printed
    assert_allclose(float(cells[("train", "output speed [rpm]")][3]), 500.0, rtol=5e-6)
    for line in md.splitlines():  # a well-formed table: every row has the header's column count
        if line.startswith("|"):
            assert line.count("|") == 6, line


@pytest.mark.parametrize("load", [9000.0, -9000.0], ids=["forward", "reversed"])
def test_lossy_three_stage_theory_is_the_driving_members_force(tmp_path, load):
    path = tmp_path / "lossy3.toml"
    path.write_text(LOSSY3.replace("LOAD", f"{load:g}"))
    code, text = _run("report", str(path), "--quick", "--format", "json")
    assert code == 0
    doc = json.loads(text)
    theory = {(c["stage"], c["quantity"]): c for c in doc["comparison"]}
    for k, forces in enumerate(_forces_by_hand(load), start=1):
        for name, f in zip(("tangential_N", "radial_N", "axial_N"), forces, strict=True):
            row = theory[(k, name)]
            assert_allclose(row["theory"], f, rtol=1e-12, err_msg=f"stage {k} {name}")
            # rigid limit (settled, unexcited): the mean meets it to the solver's accuracy (rtol 1e-6 by default)
            assert abs(row["error_percent"]) < 1e-4, row
    # the design's own static forces stay the pinion's (T_p = T_g η / i reversed): only the comparison changed
    stage3 = doc["design"]["stages"][2]["static_force_N"]["tangential"]
    eta3 = STAGES[2][4]
    expected3 = _forces_by_hand(load)[2][0] * (eta3 if load < 0 else 1.0)
    assert_allclose(stage3, expected3, rtol=1e-12)


# ------------------------------------------------------------------------------------ the accuracy study, by hand
def _spur_reference_by_scipy() -> dict[str, float]:
    """The spur scene integrated independently (scipy DOP853 at rtol 1e-13, max step 50 µs), with the mesh deflection
    δ = r_bp θ_p − r_bg θ_g as a state (integrating the angles and differencing them loses ~1e-10 of the force to
    round-off: two 6 m arc lengths for a 12 µm deflection). Gear shaft: J θ̈_g = r_bg F − T_L STEP(t, 0, 0, 0.1, 1),
    F = K δ + STEP(δ, 0, 0, d, C) δ̇ (≥ 0), K = 4e5 N/mm, C = 5 N s/mm, d = 1 µm; the input follows
    ω_p = ω_n STEP(t, 0, 0, 0.1, 1); J = π ρ b d⁴ / 32 of the gear's pitch disc (docs/design-file.md; ρ = 7800 for
    the predefined steel). Window means from the integrals carried as states, the peak over the 2001 output
    samples, as the report takes them."""
    from scipy.integrate import solve_ivp

    k, c, d_full = 4e8, 5e3, 1e-6
    cos_a = math.cos(math.radians(20))
    r_bp, r_bg = 0.042 * cos_a, 0.126 * cos_a
    inertia = math.pi * 7800 * 0.04 * 0.252**4 / 32
    w_n, ramp, load, end, w0, w1 = 1500 * math.pi / 30, 0.1, 600.0, 0.4, 0.16, 0.4

    def step(x: float, x1: float) -> float:
        s = min(max(x / x1, 0.0), 1.0)
        return s * s * (3 - 2 * s)

    def force(t: float, y) -> float:
        rate = r_bp * w_n * step(t, ramp) - r_bg * y[1]
        return max(k * y[0] + c * step(y[0], d_full) * rate, 0.0)

    def rhs(t: float, y):
        f = force(t, y)
        return [r_bp * w_n * step(t, ramp) - r_bg * y[1], (r_bg * f - load * step(t, ramp)) / inertia, f * cos_a, y[1]]

    ts = [end * i / 2000 for i in range(2001)]
    sol = solve_ivp(rhs, (0, end), [0, 0, 0, 0], method="DOP853", rtol=1e-13, atol=1e-20, t_eval=ts,
                    dense_output=True, max_step=5e-5)
    a, b = sol.sol(w0), sol.sol(w1)
    return {"output_speed_deg_s": (b[3] - a[3]) / (w1 - w0) * 180 / math.pi,
            "mean_tangential_N": (b[2] - a[2]) / (w1 - w0),
            "peak_tangential_N": max(force(t, y) * cos_a for t, y in zip(sol.t, sol.y.T, strict=True))}


@pytest.fixture(scope="module")
def spur_study(tmp_path_factory):
    path = tmp_path_factory.mktemp("spur_study") / "spur.toml"
    path.write_text(SPUR)
    code, text = _run("report", str(path), "--format", "json", "--accuracy", "1e-5")
    assert code == 0
    return json.loads(text)


def test_study_reference_within_its_stated_uncertainty_of_an_independent_solve(spur_study):
    """The study's reference (DOP853 at 1e-12, checked by Radau at 1e-10) against the independent scipy solve:
    its true error must lie within the uncertainty it states, else every "< u" and every "meets" is dishonest.
    Measured: the speed 1.4e-13 off, the mean F_t 1.7e-12, the peak 2e-14, the stated uncertainty 1.8e-12. The
    independent solve's own scatter (rtol 1e-12…1e-14, max step 50…200 µs) is 1e-13 on the mean, 1e-14 on the peak:
    allowed beside u."""
    ref = spur_study["accuracy"]["reference"]
    mine = _spur_reference_by_scipy()
    u = ref["uncertainty"]
    assert u < 1e-10  # the pair agrees closely on this linear scene
    vals = ref["values"]
    assert abs(vals["output_speed_deg_s"] - mine["output_speed_deg_s"]) <= (u + 2e-12) * mine["output_speed_deg_s"]
    # 2e-12 beside u: the round-off floor of a run at rtol 1e-12 (another engine or machine may land elsewhere in it)
    assert abs(vals["mean_tangential_N"][0] - mine["mean_tangential_N"]) <= (u + 2e-12) * mine["mean_tangential_N"]
    assert abs(vals["peak_tangential_N"][0] - mine["peak_tangential_N"]) <= (u + 2e-12) * mine["peak_tangential_N"]
    # and the rigid limit by hand: the settled mean is the static force 2 T_1 / d_1
    assert_allclose(mine["mean_tangential_N"], 2 * 200e3 / 84.0, rtol=1e-10)


def test_study_verdicts_follow_their_numbers(spur_study):
    """--accuracy 1e-5: a rung meets the target iff max(error, u) ≤ 1e-5 for the three quantities, a "< u" flag
    iff its error is below that quantity's resolution (the reference's difference from its check in it; u is
    their largest), the recommendation is a rung that meets it, and the file's verdict is its rung's."""
    acc = spur_study["accuracy"]
    assert acc["requested_accuracy"] == 1e-5
    u = acc["reference"]["uncertainty"]
    runs = [r for r in acc["runs"] if r["failure"] is None]
    assert len(runs) >= 14
    for r in runs:
        errors = (r["error_speed"], r["error_mean_force"], r["error_peak_force"])
        assert r["meets_accuracy"] == all(max(e, u) <= 1e-5 for e in errors), r
        flags = r["below_reference_resolution"]
        resolution = acc["reference"]["differences"]
        assert u == max(resolution.values())
        assert [flags["speed"], flags["mean_force"], flags["peak_force"]] == [
            e < resolution[q] for e, q in zip(errors, ("speed", "mean_force", "peak_force"), strict=True)], r
        assert r["wall_s"] >= 0 and r["nfev"] > 0
    assert acc["recommended"]["meets_accuracy"]
    file_run = next(r for r in acc["runs"] if r["file_settings"])
    assert acc["file_settings_meet_accuracy"] == file_run["meets_accuracy"]
    assert spur_study["accuracy_failure"] is None


# ----------------------------------------------------------------------------------- transmission error, by hand
TE_SPUR = """
title = "Spur stage with TE excitation"
[[stage]]
normal_module_mm = 3
normal_pressure_angle_deg = 20
helix_angle_deg = 0
pinion = { teeth = 25, face_width_mm = 30, material = "steel" }
gear   = { teeth = 50, face_width_mm = 30, material = "steel" }
[contact]
stiffness = "iso6336"
exponent = 1.0
damping_ratio = 0.05
transmission_error_um = [5.0, 1.5]
[input]
speed_rpm = 2000
ramp_s = 0.1
[load]
torque_Nm = 150
ramp_s = 0.1
[simulation]
duration_s = 0.4
"""


def test_te_mesh_orders_by_hand_and_dynamic_factor_equals_simulate(tmp_path):
    """A linear mesh on a gear whose input turns at a constant speed: the gear's mesh coordinate is a one-degree-of-
    freedom oscillator m ẍ = −k (x − e) − c (ẋ − ė) + T_L / r_bg, m = J_g / r_bg², excited through its base by the
    TE e = Σ e_h cos(h φ). The force amplitude at order h is (closed form, base excitation)
        F_h = k e_h r² √(1 + (2ζr)²) / √((1 − r²)² + (2ζr)²),  r = h ω_mesh / ω_n,  ω_n = √(k / m),
    along the line of action; F_t = F cos α (spur), the DTE amplitude F_h / k. With ζ of the mode: c = 2 ζ √(k m).
    k is the law's linearised stiffness (the simulation's mesh_stiffness), J_g = π ρ b d⁴/32 of the pitch disc."""
    path = tmp_path / "te.toml"
    path.write_text(TE_SPUR)
    code, text = _run("report", str(path), "--quick", "--format", "json")
    assert code == 0
    rep = json.loads(text)
    code, text = _run("simulate", str(path), "--format", "json")
    assert code == 0
    sim = json.loads(text)
    k = rep["simulation"]["summary"]["stages"][0]["mesh_stiffness"]["linearised_N_mm"] * 1e3  # N/m
    cos_a = math.cos(math.radians(20))
    r_bg = 0.075 * cos_a
    m = math.pi * 7800 * 0.03 * 0.150**4 / 32 / r_bg**2
    w_n, zeta = math.sqrt(k / m), 0.05
    w_mesh = 25 * 2000 * math.pi / 30
    orders = {o["order"]: o for o in rep["dynamics"][0]["spectrum"]["mesh_orders"]}
    for h, e_um in ((1, 5.0), (2, 1.5)):
        r = h * w_mesh / w_n
        amp = k * e_um * 1e-6 * r**2 * math.hypot(1, 2 * zeta * r) / math.hypot(1 - r**2, 2 * zeta * r)
        # the Hann-weighted projection over a window of ~200 mesh periods: 1 % (the windowed leakage of the other
        # order and of the ringing start)
        assert_allclose(orders[h]["tangential_N"], amp * cos_a, rtol=1e-2, err_msg=f"order {h}")
        assert_allclose(orders[h]["dte_um"], amp / k * 1e6, rtol=1e-2, err_msg=f"order {h}")
    # the report's dynamic factor is simulate's (the same run), and bounded by the static force plus both orders
    r_st, s_st = rep["dynamics"][0], sim["summary"]["stages"][0]
    for key in ("dynamic_factor", "runup_factor", "peak_tangential_N", "tangential_N"):
        assert r_st[key] == s_st[key], key
    static = 2 * 150e3 / 2 / 75.0  # pinion torque 75 N·m on d_1 = 75 mm
    assert_allclose(r_st["static_tangential_N"], static, rtol=1e-12)
    bound = (static + orders[1]["tangential_N"] + orders[2]["tangential_N"]) / static  # 3x: at Nyquist, none
    assert 1.4 < r_st["dynamic_factor"] <= bound * 1.001


def test_unexcited_mesh_orders_section_is_not_an_empty_table(spur):
    """Nothing excites the spur scene's mesh (JSON mesh_orders []): the markdown printed the section's header and no
    row, in the table format an empty box; now a row of '–' per such stage and a note say why."""
    assert spur["report"]["dynamics"][0]["spectrum"]["mesh_orders"] == []
    md = spur["markdown"].split("## Mesh-order amplitudes", 1)[1].split("\n## ", 1)[0]
    rows = [x for x in md.splitlines() if x.startswith("| ")]
    assert rows[2:] == ["| 1 | – | – | – | – |"]
    assert "no fluctuation" in md


def test_mesh_forces_plot_reversed_load_static_line_and_peak_marker(tmp_path):
    """mesh_forces.png of the reversed lossy reducer drew the static line at the design's pinion-side −7304 N
    (stage 1) beside a mean of −7453 N, and the run-up peak marker at +7454 N, above a curve that never leaves the
    negative half. The line is now the comparison's theory (the driving gear's T_g / r_g) and the marker sits on the
    curve, signed."""
    pytest.importorskip("matplotlib")
    from gearcli import api
    from gearcli.io.plots import mesh_forces_figure

    path = tmp_path / "reversed.toml"
    path.write_text(LOSSY3.replace("LOAD", "-9000"))
    loaded = api.load(str(path))
    rep = api.report_file(loaded, api.design(loaded), quick=True)
    fig = mesh_forces_figure(rep)
    hand = _forces_by_hand(-9000.0)
    axes = fig.axes
    for k in range(3):
        main = axes[2 * k] if len(axes) == 6 else axes[k]
        lines = {ln.get_label(): ln for ln in main.get_lines()}
        static = next(v for lbl, v in lines.items() if lbl.startswith("static F_t"))
        assert_allclose(static.get_ydata()[0], hand[k][0], rtol=1e-12)
        peak = next(v for lbl, v in lines.items() if lbl.startswith("run-up peak"))
        assert peak.get_ydata()[0] < 0  # on the curve: the forces of a reversed load are negative
        assert_allclose(abs(peak.get_ydata()[0]), rep.stages[k].peak_tangential_N, rtol=1e-12)


def test_mesh_order_above_nyquist_is_not_an_alias_amplitude():
    """Samples at 5 kHz (Nyquist 2.5 kHz), mesh at 1100 Hz: the 3x order (3300 Hz) cannot be held by the samples,
    and the projection onto it measured its alias 2 f_N − f = 1700 Hz instead, here a 100 N mode response, printed
    as a 100 N third mesh order. Closed form: F = 2000 + 50 cos(2π 1100 t) + 100 cos(2π 1700 t + 0.3); 1x = 50 N,
    2x (2200 Hz, below Nyquist) = 0, 3x: no amplitude (None)."""
    import numpy as np

    from gearcli.report.spectrum import mesh_orders

    t = np.arange(0, 0.4 + 1e-12, 2e-4)
    force = 2000 + 50 * np.cos(2 * np.pi * 1100 * t) + 100 * np.cos(2 * np.pi * 1700 * t + 0.3)
    orders = {o.order: o for o in mesh_orders(t, force, force / 1e3, (0.16, 0.4), 1100.0)}
    assert_allclose(orders[1].tangential_N, 50.0, rtol=1e-3)  # Hann projection: the 1700 Hz line is 145 bins away
    assert orders[2].tangential_N < 0.1
    assert orders[3].tangential_N is None and orders[3].dte_um is None
    assert orders[3].frequency_Hz == 3300.0


def test_te_report_marks_the_order_at_nyquist(tmp_path):
    """The TE scene's 3x order (2500 Hz) sits at the Nyquist frequency of its 2000 steps over 0.4 s: JSON null, the
    markdown '> Nyquist' with a note, the 1x and 2x amplitudes as before."""
    path = tmp_path / "te.toml"
    path.write_text(TE_SPUR)
    code, text = _run("report", str(path), "--quick", "--format", "json")
    assert code == 0
    orders = json.loads(text)["dynamics"][0]["spectrum"]["mesh_orders"]
    assert [o["tangential_N"] is None for o in orders] == [False, False, True]
    code, md = _run("report", str(path), "--quick", "--format", "markdown")
    assert code == 0
    assert "| 1 | 3x | 2500 | > Nyquist | > Nyquist |" in md


def test_te_mesh_orders_over_whole_periods_meet_the_closed_form_closely(tmp_path):
    """steady = "periodic": the statistics over one settled mesh period, the orders its exact Fourier coefficients;
    the base-excitation closed form of test_te_mesh_orders_by_hand… (a linear mesh: the 3x order is nil) to 1e-4
    (measured 3e-6 and 7e-6)."""
    path = tmp_path / "te.toml"
    path.write_text(TE_SPUR.replace("duration_s = 0.4", 'duration_s = 0.4\nsteady = "periodic"'))
    code, text = _run("report", str(path), "--quick", "--format", "json")
    assert code == 0
    rep = json.loads(text)
    assert rep["simulation"]["summary"]["steady"]["mode"] == "periodic"
    k = rep["simulation"]["summary"]["stages"][0]["mesh_stiffness"]["linearised_N_mm"] * 1e3
    cos_a = math.cos(math.radians(20))
    m = math.pi * 7800 * 0.03 * 0.150**4 / 32 / (0.075 * cos_a) ** 2
    w_n, zeta, w_mesh = math.sqrt(k / m), 0.05, 25 * 2000 * math.pi / 30
    orders = {o["order"]: o for o in rep["dynamics"][0]["spectrum"]["mesh_orders"]}
    for h, e_um in ((1, 5.0), (2, 1.5)):
        r = h * w_mesh / w_n
        amp = k * e_um * 1e-6 * r**2 * math.hypot(1, 2 * zeta * r) / math.hypot(1 - r**2, 2 * zeta * r)
        assert_allclose(orders[h]["tangential_N"], amp * cos_a, rtol=1e-4, err_msg=f"order {h}")
    assert orders[3]["tangential_N"] < 1e-3 * orders[1]["tangential_N"]  # the linear mesh makes no 3x


def test_work_precision_wall_column_shows_sub_millisecond_runs():
    """A compiled rung of 135 evaluations takes ~0.35 ms: the column printed "0.000" (no time at all) and the ★ note
    "(0.000 s, ...)"; below 10 ms it now keeps two significant digits, above it millisecond resolution as before."""
    from gearcli.io.report_sections import wall_text

    assert wall_text(0.00035) == "0.00035"
    assert wall_text(0.0029) == "0.0029"
    assert wall_text(0.038) == "0.038"
    assert wall_text(1.23456) == "1.235"
    assert wall_text(0.0) == "0.000"


def test_intermediate_shaft_mean_speed_is_the_window_integral(tmp_path):
    """A two-stage reducer with 8 µm of TE on its meshes: the intermediate shaft's speed swings 0.5 % in the window.
    The report's stage-1 gear speed was the plain mean of the window's samples, which counts both ends in full and
    was 3.5e-6 below the window integral (the mean DESIGN §7 and simulate take); it is now the trapezoid integral,
    which the test computes from simulate's CSV of the same file (printed to 10 digits)."""
    import numpy as np

    path = tmp_path / "two_te.toml"
    text = LOSSY3.split("[[stage]]\nnormal_module_mm = 6")[0]  # stages 1 and 2
    text += LOSSY3[LOSSY3.index("[contact]"):]
    text = (text.replace("exponent = 1.5", "exponent = 1.0")
            .replace("damping_ratio = 0.05", "damping_ratio = 0.02\ntransmission_error_um = [8.0]")
            .replace("LOAD", "2500"))
    path.write_text(text)
    code, out = _run("report", str(path), "--quick", "--format", "json")
    assert code == 0
    rep = json.loads(out)
    code, csv = _run("simulate", str(path), "--format", "csv")
    assert code == 0
    data = np.genfromtxt(csv.splitlines(), delimiter=",", names=True)
    w0, w1 = rep["simulation"]["summary"]["window_s"]
    t = data["time_s"]
    sel = (t >= w0 - 1e-9) & (t <= w1 + 1e-9)
    speed = data["shaft2_speed_rpm"][sel]
    assert speed.std() / speed.mean() > 1e-3  # the shaft does swing
    integral = float(np.sum(0.5 * (speed[1:] + speed[:-1]) * np.diff(t[sel])) / (t[sel][-1] - t[sel][0]))
    row = next(c for c in rep["comparison"] if c["stage"] == 1 and c["quantity"] == "output_speed_deg_s")
    assert_allclose(row["simulated"] / 6.0, integral, rtol=1e-9)  # rpm = °/s / 6; CSV's 10 digits
    assert abs(float(np.mean(speed)) - integral) / integral > 1e-6  # the plain mean would fail the line above


def test_mesh_orders_section_names_too_few_samples(tmp_path):
    """simulation.steps = 1 leaves the window two samples: no spectrum, for want of samples, not of fluctuation."""
    path = tmp_path / "spur.toml"
    path.write_text(SPUR.replace("steps = 2000", "steps = 1"))
    code, md = _run("report", str(path), "--quick", "--format", "markdown")
    assert code == 0
    section = md.split("## Mesh-order amplitudes", 1)[1].split("\n## ", 1)[0]
    assert "too few samples in the window" in section and "no fluctuation" not in section
