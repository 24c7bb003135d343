"""``[[duty]] starts = N`` by hand on an engineer's scene (tests/reference/starts_scene.py: a DOL 11 kW agitator
drive, every inertia given): the start's tooth-load cycles counted here from the simulated series of the point's
run from rest (each whole mesh cycle of [0, window start] one engagement at its largest |F_t|, the contract's
counting, docs/life.md "Spectra"), classed, each class rated by ``gearcli design`` at the class's own force (K_A =
K_v = 1), and its damage n/N on the ISO 6336-2 Z_NT / ISO 6336-3 Y_NT curves of case-carburized steel written out
here (Table 2 / Table 3 nodes, log-log, the last slope continued). Then: the start's damage scales with N, N = 0
adds none, the bearings' ISO 281 equivalent load and ISO 76 static safety over the duty take the start by hand."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli
from tests.reference.starts_scene import DRIVE_SCENE, HELIX_DEG, LOAD_NM, MODULE_MM, SPEED_RPM, TEETH

# σ_Hlim 1000 MPa: the steady stress (755 MPa at the pinion) lies below the endurance limit (0.85 σ_∞, σ_∞ about
# 970 MPa), the DOL start's peak (about 1120 MPa) above it: the life is finite only through the starts
SCENE = DRIVE_SCENE.replace("contact_fatigue_limit_MPa = 1500", "contact_fatigue_limit_MPa = 1000")
ZNT = ((1e5, 1.6), (5e7, 1.0), (1e10, 0.85))  # ISO 6336-2:2006 Table 2, case-carburized, normal quality
YNT = ((1e3, 2.5), (3e6, 1.0), (1e10, 0.85))  # ISO 6336-3:2006 Table 3
D_GEAR = [TEETH[1] * MODULE_MM[0] / math.cos(math.radians(HELIX_DEG[0])),
          TEETH[3] * MODULE_MM[1] / math.cos(math.radians(HELIX_DEG[1]))]
I1, I2 = TEETH[1] / TEETH[0], TEETH[3] / TEETH[2]


def _duty(*points: tuple[str, float, int]) -> str:
    return SCENE + "".join(f"\n[[duty]]\nname = \"{n}\"\nhours = 10000\nstarts = {s}\ntorque_Nm = {t!r}\n"
                           f"speed_rpm = {SPEED_RPM!r}\n" for n, t, s in points)


def _run(tmp_path, text: str, command: str, *args: str) -> dict:
    path = tmp_path / f"{abs(hash(text))}.toml"
    path.write_text(text)
    res = CliRunner().invoke(cli, ["-q", command, str(path), "--format", "json", *args])
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout)


def _cycles_to_failure(nodes, stress: float, endurance: float) -> float:
    """N on the life-factor curve through ``nodes`` (N, factor) times the endurance strength, log-log between
    the nodes, the first segment continued above the static node and the last beyond 1e10."""
    y = stress / endurance
    (n0, y0), (n1, y1), (n2, y2) = nodes
    if y >= y1:
        return n0 * (y0 / y) ** (math.log(n1 / n0) / math.log(y0 / y1))
    return n1 * (y1 / y) ** (math.log(n2 / n1) / math.log(y1 / y2))


def _engagement_peaks(t, speed_rad_s, force, teeth):
    """The largest |F| of each whole mesh cycle: the pinion's mesh phase z theta / 2 pi between two integers,
    theta the trapezoid integral of |omega| (written independently: a loop over the samples)."""
    theta = 0.0
    peaks, current, cycle = [], 0.0, 0
    for i in range(t.size):
        if i:
            theta += 0.5 * (abs(speed_rad_s[i]) + abs(speed_rad_s[i - 1])) * (t[i] - t[i - 1])
        c = int(math.floor(teeth * theta / (2 * math.pi)))
        if c != cycle:  # sample i begins a new cycle: the previous one is whole
            if cycle >= 0 and i > 0 and peaks is not None:
                peaks.append(current)
            cycle, current = c, 0.0
        current = max(current, abs(force[i]))
    return np.array(peaks)  # the first cycle began at t = 0: whole, and counted (a DOL start peaks in it)


@pytest.fixture(scope="module")
def base(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("starts_engineer")
    life = _run(tmp, _duty(("run", LOAD_NM, 100)), "life")
    point = life["life"]["points"][0]
    sv = point["solver"]
    sets = [f"input.speed_rpm={SPEED_RPM!r}", f"load.torque_Nm={LOAD_NM!r}", "load.application_factor=1",
            "rating.dynamic_factor=1.0", f"simulation.steps={sv['output_samples'] - 1}",
            f"simulation.duration_s={sv['duration_s']!r}", f"simulation.window_start_s={sv['window_s'][0]!r}"]
    sim = _run(tmp, SCENE, "simulate", "--series", *[x for s in sets for x in ("--set", s)])
    return tmp, life, sim, sets


def test_the_start_damage_from_the_simulated_series_by_hand(base):
    tmp, life, sim, sets = base
    point = life["life"]["points"][0]
    start, n_starts = point["start"], 100
    window_start = point["solver"]["window_s"][0]
    assert start["count"] == n_starts and start["span_s"] == [0.0, window_start]
    series = {k: np.asarray(v) for k, v in sim["series"].items()}
    t = series["time_s"]
    mask = t <= window_start + 1e-12
    w1 = series["shaft1_speed_rpm"][mask] * 2 * math.pi / 60
    revs = float(np.sum(0.5 * (np.abs(w1[1:]) + np.abs(w1[:-1])) * np.diff(t[mask]))) / (2 * math.pi)
    assert_allclose(start["input_revolutions"], revs, rtol=1e-9)
    for k in range(2):
        force = series[f"stage{k + 1}_tangential_N"][mask]
        # 1e-8: the re-run of the same point (same sets, same engine) agrees to 7e-10
        assert_allclose(start["peak_tangential_N"][k], np.max(np.abs(force)), rtol=1e-8)
        w_pinion = series[f"shaft{k + 1}_speed_rpm"][mask] * 2 * math.pi / 60
        peaks = _engagement_peaks(t[mask], w_pinion, force, TEETH[2 * k])
        # 20 equal-width classes from the smallest to the largest peak, each standing at its largest peak
        lo, hi = peaks.min(), peaks.max()
        idx = np.minimum(((peaks - lo) / (hi - lo) * 20).astype(int), 19)
        classes = [(float(peaks[idx == c].max()), float(np.mean(idx == c))) for c in range(20) if np.any(idx == c)]
        # load cycles of one tooth: N x the start's input revolutions x n_member / n_input x share
        speed = {"pinion": 1.0 if k == 0 else 1.0 / I1, "gear": 1.0 / I1 if k == 0 else 1.0 / (I1 * I2)}
        # each class rated by design at its own force: the output torque whose stage-k force it is (lossless)
        rated = []
        for f, share in classes:
            torque = float(f) * D_GEAR[k] / 2e3 * (I2 if k == 0 else 1.0)
            d = _run(tmp, SCENE, "design", "--set", f"load.torque_Nm={torque!r}", "--set", "load.application_factor=1",
                     "--set", "rating.dynamic_factor=1.0")
            st = d["stages"][k]
            assert_allclose(st["static_force_N"]["tangential"], f, rtol=1e-9)
            rated.append((share, st["rating"]))
        for member in ("pinion", "gear"):
            n_member = n_starts * revs * speed[member]
            for mode, nodes, key in (("pitting", ZNT, "H"), ("bending", YNT, "F")):
                hand = 0.0
                for share, r in rated:
                    m = r[member]
                    endurance = m[f"sigma_{key}G_MPa"] / m[f"{key[0].replace('H', 'Z').replace('F', 'Y')}_NT"]
                    hand += n_member * share / _cycles_to_failure(nodes, m[f"sigma_{key}_MPa"], endurance)
                # 1e-6: the reference's classes come from a re-run of the point's simulation (same sets, same
                # engine), the stresses from separate design runs
                assert_allclose(start["damage"][k][member][mode], hand, rtol=1e-6, err_msg=(k, member, mode))


def test_the_start_damage_scales_with_the_count_and_none_without_starts(tmp_path, base):
    _, life, _, _ = base
    ref = life["life"]["points"][0]["start"]
    lives = {n: _run(tmp_path, _duty(("run", LOAD_NM, n)), "life") for n in (0, 1, 100_000_000)}
    assert lives[0]["life"]["points"][0]["start"] is None
    steady = lives[0]["life"]["stages"]
    for n in (1, 100_000_000):
        doc = lives[n]["life"]
        start = doc["points"][0]["start"]
        assert start["count"] == n
        assert_allclose(start["peak_tangential_N"], ref["peak_tangential_N"], rtol=1e-12)
        for k in range(2):
            for member in ("pinion", "gear"):
                for mode in ("pitting", "bending"):
                    d_n = start["damage"][k][member][mode]
                    assert_allclose(d_n, ref["damage"][k][member][mode] * n / 100, rtol=1e-12)
                    # the duty's damage is the steady run's plus the starts' own
                    assert_allclose(doc["stages"][k][member][mode]["damage"],
                                    steady[k][member][mode]["damage"] + d_n, rtol=1e-12)
    # the steady pinion's stress lies below the endurance limit: no finite life without the starts, a finite one
    # with them (the start's peak class above the limit)
    p0, p1 = steady[0]["pinion"]["pitting"], lives[1]["life"]["stages"][0]["pinion"]["pitting"]
    assert p0["below_endurance"] is True and p0["life_h"] is None
    assert p1["below_endurance"] is False
    assert_allclose(p1["life_h"], 10000 / p1["damage"], rtol=1e-12)
    big = lives[100_000_000]["life"]["stages"][0]["pinion"]["pitting"]
    assert big["damage"] > 1 and big["load_multiplier"] < 1  # 1e8 DOL starts destroy the pinion's flanks


# bearing 5 (the output shaft's locating bearing, F_a/F_r about 0.8) with ISO 76 factors: P_0 = max(F_r, X0 F_r +
# Y0 F_a) takes its axial force
BEARING_SCENE = SCENE.replace('kind = "roller"\nlocating = true\n[[bearing]]\nshaft = 3',
                              'kind = "roller"\nlocating = true\nstatic_factors = { X0 = 0.5, Y0 = 1.0 }\n'
                              '[[bearing]]\nshaft = 3')
BEARING_DUTY = (("run", LOAD_NM, 100, 10000.0), ("light", 400.0, 300, 5000.0))


def test_bearings_over_the_duty_and_its_starts_by_hand(tmp_path):
    assert "X0 = 0.5" in BEARING_SCENE
    text = BEARING_SCENE + "".join(f"\n[[duty]]\nname = \"{n}\"\nhours = {h!r}\nstarts = {s}\ntorque_Nm = {t!r}\n"
                                   f"speed_rpm = {SPEED_RPM!r}\n" for n, t, s, h in BEARING_DUTY)
    life = _run(tmp_path, text, "life")["life"]
    # two points with different starts: each point's starts are classes of their own, named by the point, and the
    # duty's damage is the sum of every class's (the steady points' and both points' starts')
    for k, st in enumerate(life["stages"]):
        for member in ("pinion", "gear"):
            for mode in ("pitting", "bending"):
                ml = st[member][mode]
                assert_allclose(ml["damage"], sum(b["damage"] for b in ml["bins"]), rtol=1e-12)
                for (name, *_), point in zip(BEARING_DUTY, life["points"], strict=True):
                    own = [b for b in ml["bins"] if b["point"] == f"{name} (start)"]
                    assert own and all(b["damage"] > 0 for b in own)
                    assert_allclose(point["start"]["damage"][k][member][mode], sum(b["damage"] for b in own),
                                    rtol=1e-12)
    ratio = (1.0, 1.0 / I1, 1.0 / (I1 * I2))  # shaft speed over the input's
    c = [30e3, 30e3, 90e3, 90e3, 150e3, 150e3]
    c0 = [18e3, 18e3, 100e3, 100e3, 180e3, 180e3]
    p_exp = [3.0, 3.0, 10 / 3, 10 / 3, 10 / 3, 10 / 3]  # ball, roller (ISO 281)
    levels = [[] for _ in c]  # (revolutions, equivalent load) per bearing
    peaks = [0.0 for _ in c]
    for (_, torque, n_starts, hours), point in zip(BEARING_DUTY, life["points"], strict=True):
        sv = point["solver"]
        sim = _run(tmp_path, BEARING_SCENE, "simulate", "--series", *[x for s in (
            f"input.speed_rpm={SPEED_RPM!r}", f"load.torque_Nm={torque!r}", "load.application_factor=1",
            "rating.dynamic_factor=1.0", f"simulation.steps={sv['output_samples'] - 1}",
            f"simulation.duration_s={sv['duration_s']!r}", f"simulation.window_start_s={sv['window_s'][0]!r}")
            for x in ("--set", s)])
        series = {k: np.asarray(v) for k, v in sim["series"].items()}
        t = series["time_s"]
        start = t <= sv["window_s"][0] + 1e-12
        window = t >= sv["window_s"][0] - 1e-12
        w1 = np.abs(series["shaft1_speed_rpm"])
        revs = point["start"]["input_revolutions"]
        for j in range(len(c)):
            fr, fa = np.abs(series[f"bearing{j + 1}_radial_N"]), np.abs(series[f"bearing{j + 1}_axial_N"])
            p = fr  # no ISO 281 factors: P = F_r
            # the start: P^p averaged over its revolutions (the input shaft's speed the weight)
            p_start = (np.sum(p[start] ** p_exp[j] * w1[start]) / np.sum(w1[start])) ** (1 / p_exp[j])
            assert_allclose(point["start"]["bearings"][j]["equivalent_load_N"], p_start, rtol=1e-6)
            assert_allclose(point["start"]["bearings"][j]["peak_radial_N"], fr[start].max(), rtol=1e-6)
            # the steady window at the point's speed: P^p averaged over the window's samples
            p_window = np.mean(p[window] ** p_exp[j]) ** (1 / p_exp[j])
            levels[j] += [(hours * 60 * SPEED_RPM * ratio[(j // 2)], p_window),
                          (n_starts * revs * ratio[j // 2], p_start)]
            x0, y0 = (0.5, 1.0) if j == 4 else (1.0, 0.0)
            peaks[j] = max(peaks[j], float(np.max(np.maximum(fr, x0 * fr + y0 * fa))))
    hours = sum(h for *_, h in BEARING_DUTY)
    for j, b in enumerate(life["bearings"]):
        n = np.array([r for r, _ in levels[j]])
        load = np.array([x for _, x in levels[j]])
        p_eq = (np.sum(n * load ** p_exp[j]) / n.sum()) ** (1 / p_exp[j])
        l10 = (c[j] / p_eq) ** p_exp[j]  # million revolutions
        # 1e-5: the window's P from a re-run of each point (same sets, same engine)
        assert_allclose(b["revolutions"], n.sum(), rtol=1e-9, err_msg=j)
        assert_allclose(b["equivalent_load_N"], p_eq, rtol=1e-5, err_msg=j)
        assert_allclose(b["L10_Mrev"], l10, rtol=5e-5, err_msg=j)
        assert_allclose(b["L10_h"], l10 * 1e6 / (60 * n.sum() / (60 * hours)), rtol=5e-5, err_msg=j)  # at the mean rpm
        # ISO 76 over the duty and its starts: C_0 over the largest P_0 of both runs from rest (their starts)
        assert_allclose(b["static_safety_min"], c0[j] / peaks[j], rtol=1e-6, err_msg=j)


@pytest.mark.parametrize("sets, warned", [
    (("input.drive=torque", f"input.torque_Nm={LOAD_NM / (I1 * I2)!r}", "input.ramp_s=0.2"), True),
    (("input.drive=speed", "input.ramp_s=0"), True),
    (("input.drive=speed", "input.ramp_s=0.5"), False),
    ((), False),  # the file's DOL motor
])
def test_starts_on_a_drive_that_does_not_start_from_rest_are_warned(tmp_path, sets, warned):
    """A torque drive's run starts at its nominal speed, a speed drive without a ramp at its speed (docs/physics.md):
    the run before the window is then no start-up, though counted as one; the warning names the point."""
    doc = _run(tmp_path, _duty(("run", LOAD_NM, 100)), "life", *[x for s in sets for x in ("--set", s)])
    found = [w for w in doc["warnings"] if w["code"] == "starts_not_from_rest"]
    assert len(found) == (1 if warned else 0), found
    if warned:
        assert found[0]["point"] == "run" and "duty point run" in found[0]["message"]


def test_a_vfd_point_at_part_load_is_warned_off_its_speed(tmp_path):
    """A VFD's supply puts the rated torque at speed_rpm; at 30 % of the load (constant) the motor slips less and
    runs at 1491.3 rpm, 2.1 % over the point's 1460 rpm its cycle counts assume (silent for a VFD before)."""
    doc = _run(tmp_path, _duty(("run", LOAD_NM, 0), ("light", 300.0, 0)), "life", "--set", "input.starting=vfd",
               "--set", "input.ramp_s=1.5", "--set", "input.torque_limit_Nm=150")
    found = [w for w in doc["warnings"] if w["code"] == "motor_speed_mismatch"]
    assert [w["point"] for w in found] == ["light"], found
    assert found[0]["operating_speed_rpm"] > 1.02 * SPEED_RPM and "VFD" in found[0]["message"]


@pytest.mark.parametrize("starts, said", [(250, True), (0, False)])
def test_a_history_replacing_tables_with_starts_says_the_starts_are_not_counted(tmp_path, starts, said):
    """--series replaces the [[duty]] tables (docs/life.md); their starts went with them without a word."""
    history = tmp_path / "history.csv"
    history.write_text("time_s,torque_Nm,speed_rpm\n0,1000,1460\n36000000,300,1460\n72000000,0,1460\n")
    doc = _run(tmp_path, _duty(("run", LOAD_NM, starts)), "life", "--static", "--series", str(history))
    found = [w for w in doc["warnings"] if "[[duty]] starts" in w["message"]]
    assert len(found) == (1 if said else 0), found
    if said:
        assert found[0]["code"] == "duty" and f"their {starts} starts" in found[0]["message"]
        assert all(p["start"] is None for p in doc["life"]["points"])


def test_a_quiet_window_is_one_class_at_the_static_force(base):
    """No excitation: every engagement of the settled window meets the static force (the design's F_t = 2 T / d,
    lossless), to the integration's noise; that is one class, not 20 of the same force 5e-10 apart."""
    _, life, _, _ = base
    for k in range(2):
        static = LOAD_NM / (I2 if k == 0 else 1.0) * 2e3 / D_GEAR[k]  # the torque on gear k over its radius
        for member, per_turn in (("pinion", 1.0 if k == 0 else 1 / I1), ("gear", 1 / I1 if k == 0 else 1 / (I1 * I2))):
            steady = [b for b in life["life"]["stages"][k][member]["pitting"]["bins"] if b["point"] == "run"]
            assert len(steady) == 1, (k, member, len(steady))
            assert_allclose(steady[0]["force_N"], static, rtol=1e-6)
            assert_allclose(steady[0]["cycles"], 10000 * 60 * SPEED_RPM * per_turn, rtol=1e-12)


def test_a_periodic_steady_state_counts_a_slow_stages_mesh_cycles(tmp_path):
    """steady = "periodic": the window is one period of the state, here one stage-2 mesh period (8.5 ms), which holds
    no whole stage-2 mesh cycle between its boundaries: every multi-stage duty stopped with exit 2 ("lengthen
    simulation.duration_s", which cannot help). The orbit repeated gives the spectrum: the quiet drive's static
    forces by hand, the cycles hours x 60 x n, as the window route's."""
    doc = _run(tmp_path, _duty(("run", LOAD_NM, 0)), "life", "--set", "simulation.steady=periodic")
    point = doc["life"]["points"][0]
    assert min(point["mesh_cycles"]) >= 40
    for k in range(2):
        static = LOAD_NM / (I2 if k == 0 else 1.0) * 2e3 / D_GEAR[k]
        bins = doc["life"]["stages"][k]["gear"]["pitting"]["bins"]
        assert len(bins) == 1
        assert_allclose(bins[0]["force_N"], static, rtol=1e-6)
        assert_allclose(bins[0]["cycles"], 10000 * 60 * SPEED_RPM / (I1 if k == 0 else I1 * I2), rtol=1e-12)
