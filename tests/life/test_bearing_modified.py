"""ISO 281 modified life and ISO 76 static safety of the [[bearing]] tables in `design`, `simulate` and `life`,
against hand calculations from the bearings' reactions (docs/bearings.md).

The hand calculations use the standard's formulas written out here: nu_1 = 4500 n^-0.5 d_m^-0.5 (n >= 1000
r/min, ISO 281 6.5.2.4), a_ISO of a radial ball bearing (ISO 281 eq. 10, 1 <= kappa <= 4), the oil at its
temperature by ASTM D341, P_0 = max(F_r, X_0 F_r + Y_0 F_a) (ISO 76) and s_0 = C_0 / P_0.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli
from tests.life.scenes import RATED, design_of

C0_KN, CU_KN, DM, X0, Y0 = 45.0, 1.6, 80.0, 0.6, 0.5
NU40, NU100, TEMP = 220.0, 19.0, 80.0
TODAY_KEYS = {"shaft", "position_mm", "radial_N", "radial_y_N", "radial_z_N", "axial_N", "equivalent_load_N",
              "L10_Mrev", "L10_h", "kind", "locating", "dynamic_load_rating_kN", "speed_rpm"}
NEW_KEYS = {"kappa", "a_ISO", "a_1", "L_nm_Mrev", "L_nm_h", "static_equivalent_load_N", "static_safety"}


def _with_keys(text: str = RATED, *, contamination: str = 'contamination = "normal"') -> str:
    """RATED with the new keys on bearing 1 (the input shaft's locating ball bearing) and the oil."""
    text = text.replace("viscosity_40C_mm2_s = 220", f"viscosity_40C_mm2_s = {NU40}\nviscosity_100C_mm2_s = "
                        f"{NU100}\ntemperature_C = {TEMP}\n{contamination}")
    return text.replace("factors = { e = 0.3, X = 0.56, Y = 1.5 }",
                        "factors = { e = 0.3, X = 0.56, Y = 1.5 }\n"
                        f"static_load_rating_kN = {C0_KN}\nfatigue_load_limit_kN = {CU_KN}\npitch_diameter_mm = {DM}\n"
                        f"reliability_percent = 95\nstatic_factors = {{ X0 = {X0}, Y0 = {Y0} }}", 1)


def _nu_at(t_c: float) -> float:
    """ASTM D341 through the 40 and 100 °C values, by hand."""
    w = [math.log10(math.log10(v + 0.7)) for v in (NU40, NU100)]
    b = (w[1] - w[0]) / (math.log10(373.15) - math.log10(313.15))
    return 10 ** 10 ** (w[0] + b * (math.log10(t_c + 273.15) - math.log10(313.15))) - 0.7


def _ball_a_iso(kappa: float, x: float) -> float:
    assert 1.0 <= kappa <= 4.0  # ISO 281 eq. (10)
    return min(0.1 * (1 - (2.5671 - 1.9987 / kappa**0.071739) ** 0.83 * x ** (1 / 3)) ** -9.3, 50.0)


def _run(tmp_path, command: str, text: str, *args: str):
    path = tmp_path / "scene.toml"
    path.write_text(text)
    return CliRunner().invoke(cli, [command, str(path), *args])


def _json(tmp_path, command: str, text: str, *args: str) -> dict:
    res = _run(tmp_path, command, text, "--format", "json", *args)
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout)


def _hand(b: dict) -> dict:
    """The new figures of bearing 1 from its reactions in the design JSON, by hand."""
    fr, fa, n = b["radial_N"], abs(b["axial_N"]), b["speed_rpm"]
    p0 = max(fr, X0 * fr + Y0 * fa)
    kappa = _nu_at(TEMP) / (4500 * n**-0.5 * DM**-0.5)
    a_iso = _ball_a_iso(kappa, 0.5 * CU_KN * 1e3 / b["equivalent_load_N"])  # "normal", d_m < 100 mm: e_C 0.5
    l_nm = 0.64 * a_iso * b["L10_Mrev"]  # a_1 at 95 % (ISO 281 Table 12)
    return {"static_equivalent_load_N": p0, "static_safety": C0_KN * 1e3 / p0, "kappa": kappa, "a_ISO": a_iso,
            "a_1": 0.64, "L_nm_Mrev": l_nm, "L_nm_h": l_nm * 1e6 / (60 * n)}


def test_design_adds_the_figures_by_hand(tmp_path):
    doc = _json(tmp_path, "design", _with_keys())
    first, others = doc["bearings"][0], doc["bearings"][1:]
    assert NEW_KEYS <= set(first)
    for key, value in _hand(first).items():
        assert_allclose(first[key], value, rtol=1e-12, err_msg=key)
    for b in others:  # bearings without the keys: today's output
        assert set(b) == TODAY_KEYS


def test_without_the_new_keys_the_bearings_are_todays(tmp_path):
    doc = _json(tmp_path, "design", RATED)
    assert all(set(b) == TODAY_KEYS for b in doc["bearings"])
    table = _run(tmp_path, "design", RATED, "--format", "table").stdout
    assert "a_ISO" not in table and "s_0" not in table and "K_γ" not in table


def test_the_table_prints_every_new_figure(tmp_path):
    table = _run(tmp_path, "design", _with_keys(), "--format", "table").stdout
    for label in ("viscosity ratio κ", "a_ISO (ISO 281)", "a_1 (reliability)", "L_nm [10^6 rev]", "L_nmh [h]",
                  "static equivalent P_0 [N]", "static safety s_0 = C_0/P_0"):
        assert label in table, label


@pytest.mark.parametrize(("edit", "key"), [
    (lambda t: t.replace(f"pitch_diameter_mm = {DM}\n", ""), "bearing[0].pitch_diameter_mm"),
    (lambda t: t.replace(f"temperature_C = {TEMP}\n", ""), "lubricant.temperature_C"),
    (lambda t: t.replace(f"viscosity_100C_mm2_s = {NU100}\n", ""), "lubricant.viscosity_100C_mm2_s"),
    (lambda t: t.replace('contamination = "normal"\n', ""), "lubricant.contamination"),
    (lambda t: t.replace('contamination = "normal"', 'contamination = "clean"'), "contamination"),
    (lambda t: t.replace('contamination = "normal"', 'contamination = "normal"\ne_C = 0.4'), "lubricant"),
    (lambda t: t.replace(f"static_load_rating_kN = {C0_KN}\n", ""), "bearing[0].static_load_rating_kN"),
])
def test_missing_or_bad_input_is_exit_2_naming_the_key(tmp_path, edit, key):
    res = _run(tmp_path, "design", edit(_with_keys()), "--format", "json")
    assert res.exit_code == 2, res.output
    assert key in res.stderr and "Traceback" not in res.stderr


def test_e_c_given_replaces_the_level(tmp_path):
    b = _json(tmp_path, "design", _with_keys(contamination="e_C = 0.35"))["bearings"][0]
    kappa = _nu_at(TEMP) / (4500 * b["speed_rpm"] ** -0.5 * DM**-0.5)
    assert_allclose(b["a_ISO"], _ball_a_iso(kappa, 0.35 * CU_KN * 1e3 / b["equivalent_load_N"]), rtol=1e-12)


def test_static_safety_below_the_minimum_warns(tmp_path):
    """A ball bearing's default minimum is 1.0 (docs/bearings.md); [rating] min_static_safety_bearing moves it."""
    b = _json(tmp_path, "design", _with_keys())["bearings"][0]
    s0 = b["static_safety"]
    for minimum, warns in ((None, s0 < 1.0), (s0 * 1.01, True), (s0 * 0.99, False)):
        text = _with_keys()
        if minimum is not None:
            text = text.replace("required_life_h = 20000", f"required_life_h = 20000\nmin_static_safety_bearing = "
                                f"{minimum!r}")
        codes = [w["code"] for w in _json(tmp_path, "design", text)["warnings"]]
        assert ("bearing_static_safety_low" in codes) == warns, minimum
    # a small C_0 warns with the default
    low = _with_keys().replace(f"static_load_rating_kN = {C0_KN}", f"static_load_rating_kN = {s0 * C0_KN * 0.5}")
    low = low.replace(f"static_load_rating_kN = {s0 * C0_KN * 0.5}", f"static_load_rating_kN = {C0_KN / s0 * 0.5!r}")
    doc = _json(tmp_path, "design", low)
    assert_allclose(doc["bearings"][0]["static_safety"], 0.5, rtol=1e-9)
    assert "bearing_static_safety_low" in [w["code"] for w in doc["warnings"]]


def test_simulate_static_safety_at_the_window_peak(tmp_path):
    """summary.bearings[0].static_safety_min = C_0 / max over the window of P_0(t), P_0(t) from the simulated
    bearing channels (radial and axial) by ISO 76, to 1e-9."""
    from gearcli.api import simulate_file
    from gearcli.config import load_design
    from gearcli.design import compute_design

    text = _with_keys() + "\n"
    path = tmp_path / "scene.toml"
    path.write_text(text)
    loaded = load_design(str(path))
    design = compute_design(loaded.design)
    result = simulate_file(loaded, design)
    t = result.time_s
    mask = (t >= result.window_s[0]) & (t <= result.window_s[1])
    from gearcli.core.channels import Channel

    fr = result.series[Channel("radial_force", "bearing1")][mask]
    fa = result.series[Channel("axial_force", "bearing1")][mask]
    peak = np.max(np.maximum(fr, X0 * fr + Y0 * np.abs(fa)))
    stats = result.extra["bearings"][0]
    assert_allclose(stats["static_safety_min"], C0_KN * 1e3 / peak, rtol=1e-9)
    assert "static_safety_min" not in result.extra["bearings"][1]  # no C_0: no key
    # the JSON carries it
    doc = _json(tmp_path, "simulate", text)
    assert_allclose(doc["summary"]["bearings"][0]["static_safety_min"], C0_KN * 1e3 / peak, rtol=1e-9)


def test_life_over_the_duty_by_hand(tmp_path):
    """Static route: per point its own design's P and speed give a_ISO; L_nm = N / sum(n_i / L_nm,i)
    (Palmgren–Miner, ISO 281 for variable conditions); s_0 at the largest P_0 of the points."""
    from tests.life.test_life_cli import POINTS

    text = _with_keys()
    life = _json(tmp_path, "life", text, "--static", "-q")["life"]["bearings"]
    b = life[0]
    revs, damage, p0s = [], [], []
    for _, hours, torque, speed in POINTS:
        _, d = design_of(text, (f"input.speed_rpm={speed!r}", f"load.torque_Nm={torque!r}"))
        point = d.bearings[0]
        doc = {"radial_N": point.radial_N, "axial_N": point.axial_N, "speed_rpm": point.speed_rpm,
               "equivalent_load_N": point.equivalent_load_N, "L10_Mrev": point.L10_Mrev}
        hand = _hand(doc)
        revs.append(hours * 60 * speed / 1e6)
        damage.append(revs[-1] / hand["L_nm_Mrev"])
        p0s.append(hand["static_equivalent_load_N"])
    l_nm = sum(revs) / sum(damage)
    assert_allclose(b["L_nm_Mrev"], l_nm, rtol=1e-12)
    assert_allclose(b["L_nm_h"], l_nm * 1e6 / (sum(revs) * 1e6 / 20000.0 * 1 / 60) / 60, rtol=1e-12)
    assert_allclose(b["a_ISO"], l_nm / (0.64 * b["L10_Mrev"]), rtol=1e-12)
    assert_allclose(b["static_equivalent_load_N"], max(p0s), rtol=1e-12)
    assert_allclose(b["static_safety"], C0_KN * 1e3 / max(p0s), rtol=1e-12)
    assert len(b["kappa_points"]) == 3 and b["kappa"] == min(b["kappa_points"])
    assert all(set(x) == {"shaft", "position_mm", "kind", "dynamic_load_rating_kN", "equivalent_load_N",
                          "revolutions", "L10_Mrev", "L10_h", "loads_N"} for x in life[1:])


def test_life_counts_the_starts_given_to_it(tmp_path, monkeypatch):
    """The starts' entry (``start_bearings``, made from each point's start record): one
    point's starts with a peak P_0 twice the duty's halve s_0, and their revolutions at their own load and speed
    are one more Palmgren–Miner level of L10 and L_nm (checked by hand from the points' own levels)."""
    from gearcli.life import run
    from gearcli.life.bearings import StartBearings

    text = _with_keys()
    base = _json(tmp_path, "life", text, "--static", "-q")["life"]["bearings"][0]
    n_b = 4  # RATED has four bearings
    p_start, n_start, rpm_start = 1.5 * max(base["loads_N"]), 2e6, 750.0
    start = StartBearings(1, (n_start,) * n_b, (p_start,) * n_b, (rpm_start,) * n_b,
                          (2 * base["static_equivalent_load_N"],) * n_b)
    monkeypatch.setattr(run, "start_bearings", lambda points: [start])
    started = _json(tmp_path, "life", text, "--static", "-q")["life"]["bearings"][0]
    assert_allclose(started["static_safety"], base["static_safety"] / 2, rtol=1e-12)
    assert_allclose(started["revolutions"], base["revolutions"] + n_start, rtol=1e-12)
    # L10: the starts' level joins the p-mean (ball: p = 3)
    p_eq = ((base["equivalent_load_N"] ** 3 * base["revolutions"] + p_start**3 * n_start)
            / (base["revolutions"] + n_start)) ** (1 / 3)
    assert_allclose(started["equivalent_load_N"], p_eq, rtol=1e-12)
    # L_nm: the points' damage (their revolutions over their L_nm) plus the starts' level by hand
    kappa = _nu_at(TEMP) / (4500 * rpm_start**-0.5 * DM**-0.5) if rpm_start >= 1000 else \
        _nu_at(TEMP) / (45000 * rpm_start**-0.83 * DM**-0.5)
    l_nm_start = 0.64 * _ball_a_iso(kappa, 0.5 * CU_KN * 1e3 / p_start) * (60.0 / (p_start / 1e3)) ** 3
    damage = base["revolutions"] / 1e6 / base["L_nm_Mrev"] + n_start / 1e6 / l_nm_start
    assert_allclose(started["L_nm_Mrev"], (base["revolutions"] + n_start) / 1e6 / damage, rtol=1e-12)


def test_life_dynamic_route_of_a_quiet_scene_agrees_with_the_static(tmp_path):
    """Without excitation the simulated bearing loads settle on the static ones: the dynamic route's L_nm and
    s_0 (at the window's peak P_0, never below the static load's by more than the ripple) agree with the static
    route's to the run's 1e-3 statistics target (L_nm ∝ about P^-p a_ISO(P): a few times that)."""
    text = _with_keys()
    dyn = _json(tmp_path, "life", text, "-q")["life"]["bearings"][0]
    static = _json(tmp_path, "life", text, "--static", "-q")["life"]["bearings"][0]
    assert_allclose(dyn["L_nm_Mrev"], static["L_nm_Mrev"], rtol=1e-2)
    assert_allclose(dyn["static_safety"], static["static_safety"], rtol=1e-2)
    assert dyn["static_equivalent_load_N"] >= static["static_equivalent_load_N"] * (1 - 1e-3)
