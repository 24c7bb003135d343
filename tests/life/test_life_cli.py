"""``gearcli life``: the static route against the rating and the standard's S–N curves by hand, the dynamic
route against the static one, a measured history against the same duty as tables, and bad input."""

from __future__ import annotations

import json
import math

import pytest
from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli
from tests.life.scenes import EXCITED, RATED, design_of

RATIO = 3.0  # z2 / z1 = 60 / 20
POINTS = [("light", 8000.0, 1500.0, 1500.0), ("nominal", 10000.0, 2400.0, 1500.0),
          ("peak", 2000.0, 140e3 / (1200.0 * 2 * math.pi / 60 / RATIO), 1200.0)]  # power_kW at the output speed
# ISO 6336-2:2006 Table 2 (Z_NT) and ISO 6336-3:2006 Table 3 (Y_NT), case-carburized, normal quality:
# static value, knee, 0.85 at 1e10
ZNT = ((1e5, 1.6), (5e7, 1.0), (1e10, 0.85))
YNT = ((1e3, 2.5), (3e6, 1.0), (1e10, 0.85))


def _life(tmp_path, text: str, *args: str) -> dict:
    path = tmp_path / "scene.toml"
    path.write_text(text)
    res = CliRunner().invoke(cli, ["life", str(path), "--format", "json", "-q", *args])
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout)


def _cycles_to_failure(ratio: float, nodes) -> float:
    """Invert the life factor curve by hand: factor = y_a (N_a / N)^q on each branch, q from the nodes; the
    last branch's slope continues beyond 1e10 (ISO 6336-6 as gearcli's default variant states)."""
    (n0, y0), (n1, y1), (n2, y2) = nodes
    if ratio >= y1:
        return n0 * (y0 / ratio) ** (math.log(n1 / n0) / math.log(y0 / y1))
    return n1 * (y1 / ratio) ** (math.log(n2 / n1) / math.log(y1 / y2))


def test_static_three_point_duty(tmp_path):
    doc = _life(tmp_path, RATED, "--static")["life"]
    assert doc["route"] == "static" and "Miner" in doc["miner"]
    stage = doc["stages"][0]
    total_h = sum(p[1] for p in POINTS)
    for member, speed_of in (("pinion", lambda n: n), ("gear", lambda n: n / RATIO)):
        for mode, nodes in (("pitting", ZNT), ("bending", YNT)):
            ml = stage[member][mode]
            assert len(ml["bins"]) == 3  # one bin per duty point
            damage, below = 0.0, True
            for b, (name, hours, torque, speed) in zip(ml["bins"], POINTS, strict=True):
                assert b["point"] == name
                assert_allclose(b["cycles"], hours * 60.0 * speed_of(speed), rtol=1e-12)
                # the rating of `design` at this point's load, K_A = 1
                _, d = design_of(RATED, (f"input.speed_rpm={speed!r}", f"load.torque_Nm={torque!r}",
                                         "load.application_factor=1.0"))
                m = getattr(d.stages[0].rating, member)
                stress = m.sigma_H_MPa if mode == "pitting" else m.sigma_F_MPa
                assert_allclose(b["stress_MPa"], stress, rtol=1e-12)
                assert_allclose(b["force_N"], abs(d.stages[0].static_force_N.tangential), rtol=1e-12)
                endurance = m.sigma_HG_MPa / m.Z_NT if mode == "pitting" else m.sigma_FG_MPa / m.Y_NT
                n_f = _cycles_to_failure(stress / endurance, nodes)
                assert_allclose(b["cycles_to_failure"], n_f, rtol=1e-9)
                damage += b["cycles"] / n_f
                below = below and stress / endurance < nodes[-1][1]  # under the curve's last node (0.85 at 1e10)
            assert_allclose(ml["damage"], damage, rtol=1e-9)
            assert ml["below_endurance"] == below
            if below:  # every class under the endurance limit: an infinite life, never hours / 1e-40
                assert ml["life_h"] is None
            else:
                assert_allclose(ml["life_h"], total_h / damage, rtol=1e-9)


def test_static_safety_makes_the_damage_one(tmp_path):
    """The spectrum safety s: scaling every force by s (sigma_H by sqrt(s), sigma_F by s) gives D = 1."""
    ml = _life(tmp_path, RATED, "--static")["life"]["stages"][0]["pinion"]["pitting"]
    s = ml["safety"]
    d = sum(b["cycles"] / _cycles_to_failure(b["stress_MPa"] * math.sqrt(s) / b["endurance_MPa"], ZNT)
            for b in ml["bins"])
    assert_allclose(d, 1.0, rtol=1e-8)


@pytest.mark.parametrize(("scene", "margin"), [(EXCITED, 2.0), (RATED, 1.0 - 1e-4)])
def test_dynamic_spectrum_never_less_damage_than_static_with_kv_1(tmp_path, scene, margin):
    """Each mesh cycle is counted at its largest force, which is at least the cycle's mean; the window mean
    equals the static force (a lossless mesh), and the damage is convex in the force, so the dynamic damage
    is at least the static damage at K_v = 1. The excited scene (transmission error at the mesh's 1x and 3x
    orders, the 3x near the 1481 Hz mesh mode at 1500 rpm) must show it plainly (more than twice); the quiet
    one (no excitation: the force is the static one to the solver's rtol 1e-6, and D ∝ F^16 for pitting)
    to within 1e-4."""
    dyn = _life(tmp_path, scene)["life"]
    static = _life(tmp_path, scene, "--static", "--set", "rating.dynamic_factor=1.0")["life"]
    assert dyn["route"] == "dynamic"
    for member in ("pinion", "gear"):
        for mode in ("pitting", "bending"):
            d_dyn = dyn["stages"][0][member][mode]["damage"]
            d_st = static["stages"][0][member][mode]["damage"]
            assert d_dyn >= margin * d_st, (member, mode, d_dyn, d_st)
    for p in dyn["points"]:
        assert p["mesh_cycles"][0] >= 40 and p["solver"]["rtol"] == 1e-6
        # K_v's error from the output sampling (the window max's, over the static force): the quiet scene's force
        # is constant to the solver's 1e-6, and a peak between samples exceeds them by at most the step to a
        # neighbour, so its K_v is sampled to ~1e-6; the excited one has 128 samples per mesh cycle
        k_v_err = p["solver"]["k_v_sampling_error"]
        assert len(k_v_err) == 1 and 0.0 <= k_v_err[0] <= (1e-5 if scene is RATED else 1e-2)
        if not p["solver"]["statistics_resolved"]:
            assert 1 in p["solver"]["unresolved_stages"]


def test_series_gives_the_same_life_as_the_duty_tables(tmp_path):
    """A history at three levels, each held as long as the [[duty]] point it copies, gives the same
    spectrum (each level its own torque class)."""
    csv = tmp_path / "history.csv"
    t1, t2, t3 = 8000 * 3600.0, 18000 * 3600.0, 20000 * 3600.0
    csv.write_text("time_s,torque_Nm,speed_rpm\n"
                   f"0,1500,1500\n{t1},2400,1500\n{t2},{POINTS[2][2]!r},1200\n{t3},0,0\n")
    from_series = _life(tmp_path, RATED, "--static", "--series", str(csv))["life"]
    from_tables = _life(tmp_path, RATED, "--static")["life"]
    for member in ("pinion", "gear"):
        for mode in ("pitting", "bending"):
            assert_allclose(from_series["stages"][0][member][mode]["damage"],
                            from_tables["stages"][0][member][mode]["damage"], rtol=1e-9)
    assert_allclose(from_series["hours"], 20000.0, rtol=1e-12)


def test_bearings_over_the_duty(tmp_path):
    """ISO 281 over the duty: P = (sum P_i^p N_i / sum N_i)^(1/p) from each point's static P_i (design)."""
    doc = _life(tmp_path, RATED, "--static")["life"]
    b = doc["bearings"][0]  # shaft 1, ball
    loads, revs = [], []
    for _, hours, torque, speed in POINTS:
        _, d = design_of(RATED, (f"input.speed_rpm={speed!r}", f"load.torque_Nm={torque!r}"))
        loads.append(d.bearings[0].equivalent_load_N)
        revs.append(hours * 60 * speed)
    p = (sum(x**3 * n for x, n in zip(loads, revs, strict=True)) / sum(revs)) ** (1 / 3)
    assert_allclose(b["equivalent_load_N"], p, rtol=1e-12)
    assert_allclose(b["L10_Mrev"], (60e3 / p) ** 3, rtol=1e-12)
    assert_allclose(b["L10_h"], (60e3 / p) ** 3 * 1e6 / (sum(revs) / 20000.0), rtol=1e-12)


@pytest.mark.parametrize(("edit", "where"), [
    (lambda t: t.replace("[rating]\nrequired_life_h = 20000\n", ""), "rating"),
    (lambda t: t.split("[[duty]]")[0], "duty"),
    (lambda t: t.replace('name = "light"', 'name = "light"\npower_kW = 10'), "duty[0]"),
    (lambda t: t.replace('name = "light"', 'name = "light"\nset = { "stage.0.pinion.teth" = 21 }'), "duty[0]"),
])
def test_bad_duty_is_exit_2_naming_the_key(tmp_path, edit, where):
    path = tmp_path / "bad.toml"
    path.write_text(edit(RATED))
    res = CliRunner().invoke(cli, ["life", str(path), "--static", "--format", "json"])
    assert res.exit_code == 2, res.output
    assert where in res.stderr and str(path) in res.stderr and "Traceback" not in res.stderr


def test_series_without_a_column_is_exit_2(tmp_path):
    path, csv = tmp_path / "s.toml", tmp_path / "h.csv"
    path.write_text(RATED)
    csv.write_text("time_s,torque_Nm\n0,1\n1,2\n")
    res = CliRunner().invoke(cli, ["life", str(path), "--static", "--series", str(csv)])
    assert res.exit_code == 2 and "speed_rpm" in res.stderr and str(csv) in res.stderr


def test_tables_and_plots(tmp_path):
    """The table output carries the ISO 6336-6 spectrum table and the bearings; --plots writes two PNGs."""
    path = tmp_path / "scene.toml"
    path.write_text(RATED)
    plots = tmp_path / "figures"
    res = CliRunner().invoke(cli, ["life", str(path), "--static", "--format", "table", "--plots", str(plots)])
    assert res.exit_code == 0, res.output
    assert "load spectrum and Miner damage" in res.stdout and "bearings over the duty, ISO 281" in res.stdout
    pytest.importorskip("matplotlib")
    for name in ("pitting.png", "bending.png"):
        assert (plots / name).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_design_prints_the_bearing_table(tmp_path):
    path = tmp_path / "scene.toml"
    path.write_text(RATED)
    res = CliRunner().invoke(cli, ["design", str(path), "--format", "table"])
    assert res.exit_code == 0 and "bearings: static reactions and ISO 281 life" in res.stdout


def test_dynamic_bearing_loads_of_a_quiet_scene_equal_the_static_ones(tmp_path):
    """Without excitation the simulated mesh force settles on the static one, so each point's p-mean of the
    bearing load over the window is the static equivalent load (to the run's 1e-3 statistics target)."""
    dyn = _life(tmp_path, RATED)["life"]["bearings"]
    static = _life(tmp_path, RATED, "--static")["life"]["bearings"]
    for a, b in zip(dyn, static, strict=True):
        assert_allclose(a["loads_N"], b["loads_N"], rtol=1e-3)
        assert_allclose(a["L10_h"], b["L10_h"], rtol=4e-3)  # L10 ∝ P^-p, p <= 10/3


def test_the_mixer_duty_config(tmp_path):
    """configs/mixer_duty.toml: three duty points, bearings on every shaft, a finite life for every member."""
    from pathlib import Path

    cfg = Path(__file__).resolve().parents[2] / "configs" / "mixer_duty.toml"
    res = CliRunner().invoke(cli, ["life", str(cfg), "--static", "--format", "json", "-q"])
    assert res.exit_code == 0, res.output
    doc = json.loads(res.stdout)["life"]
    assert len(doc["stages"]) == 3 and len(doc["bearings"]) == 8 and doc["hours"] == 16500
    for st in doc["stages"]:
        for member in ("pinion", "gear"):
            for mode in ("pitting", "bending"):
                ml = st[member][mode]
                assert len(ml["bins"]) == 3 and ml["damage"] > 0 and ml["safety"] > 1


def test_a_load_reversal_warning_names_its_point(tmp_path):
    """docs/output.md, "Warnings": a duty point's warnings carry its name as ``point`` (DESIGN §12: a warning's data
    beside its message). The load-reversal warning named the point in its message only (trial tr24h). The point's
    bins stand at its |torque| on the drive flanks, by hand: T_pinion = 350 / 3 N·m on the 20-tooth pinion's pitch
    radius 20 x 4 / cos 15° / 2 mm, F_t = 2813.1 N."""
    text = RATED + '\n[[duty]]\nname = "reverse"\nhours = 500\ntorque_Nm = -350\nspeed_rpm = 1500\n'
    path = tmp_path / "scene.toml"
    path.write_text(text)
    res = CliRunner().invoke(cli, ["life", str(path), "--static", "--format", "json"])
    assert res.exit_code == 0, res.output
    doc = json.loads(res.stdout)
    (rev,) = [w for w in doc["warnings"] if w["code"] == "duty" and "load reversal" in w["message"]]
    assert rev["point"] == "reverse" and rev["key"] == "duty[3]" and rev["torque_Nm"] == -350.0
    assert rev["stage"] is None
    assert f"warning: {rev['message']}" in res.stderr.splitlines()  # the same warning, in the stderr's words
    r_pinion_mm = 20 * 4 / math.cos(math.radians(15)) / 2
    (bin_,) = [b for b in doc["life"]["stages"][0]["pinion"]["pitting"]["bins"] if b["point"] == "reverse"]
    assert_allclose(bin_["force_N"], 350e3 / 3 / r_pinion_mm, rtol=1e-9)
