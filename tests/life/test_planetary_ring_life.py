"""``life --static`` on a planetary stage: the planet–ring mesh's members against hand calculations
(docs/life.md, "Planetary stages").

Scene: configs/planetary_duty.toml, the NREL 5 MW gearbox's stage 1 (sun 19, three planets 17, ring 56 held,
the carrier driving) over three duty points. With the ring held and the carrier at n_c (the duty's input
speed): the ring turns at n_c relative to the carrier, and a ring tooth meets all N = 3 planets per relative
turn: N_ring = hours × 60 × n_c × 3; the planet turns at n_c z_r / z_p relative to the carrier (Willis: n_s − n_c
= n_c z_r / z_s, times z_s / z_p) and meets the ring once per relative turn on its ring-side flank.
Each bin's stress is the planet–ring rating of `gearcli design` at the point's load with K_A = 1; its cycles to
failure invert the ISO 6336-2:2006 Table 2 / ISO 6336-3:2006 Table 3 life-factor curves written out below
(normal quality: the last slope continued beyond 1e10, gearcli's default variant).
"""

from __future__ import annotations

import json
import math
from pathlib import Path

from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli
from tests.life.scenes import design_of

CONFIG = Path(__file__).resolve().parents[2] / "configs" / "planetary_duty.toml"
Z_S, Z_P, Z_R, N = 19, 17, 56, 3
POINTS = [("rated", 50000.0, 999650.9, 12.127), ("part", 120000.0, 600000.0, 10.5),
          ("gust", 5200.0, 1250000.0, 12.127)]  # name, hours, load torque (sun), input speed (carrier)
HOURS = sum(p[1] for p in POINTS)
# (N, factor) nodes: static, knee, 1e10
ZNT = ((1e5, 1.6), (5e7, 1.0), (1e10, 0.85))  # ISO 6336-2 Table 2: St, V, GS, GGG, Eh, IF
YNT_THROUGH = ((1e4, 2.5), (3e6, 1.0), (1e10, 0.85))  # ISO 6336-3 Table 3: V (the ring, 34CrNiMo6)
YNT_CASE = ((1e3, 2.5), (3e6, 1.0), (1e10, 0.85))  # ISO 6336-3 Table 3: Eh (the planet, 18CrNiMo7-6)


def _cycles_to_failure(ratio: float, nodes) -> float:
    """Invert factor = y_a (N_a / N)^q on the branch the stress ratio falls on (above the static node the
    finite-life branch is extrapolated, as gearcli does with a warning)."""
    (n0, y0), (n1, y1), (n2, y2) = nodes
    if ratio >= y1:
        return n0 * (y0 / ratio) ** (math.log(n1 / n0) / math.log(y0 / y1))
    return n1 * (y1 / ratio) ** (math.log(n2 / n1) / math.log(y1 / y2))


def _run(*args: str) -> tuple[int, str, str]:
    res = CliRunner().invoke(cli, ["life", str(CONFIG), "-q", *args], env={"COLUMNS": "250"})  # tables unfolded
    return res.exit_code, res.stdout, res.stderr


def _doc() -> dict:
    code, out, err = _run("--static", "--format", "json")
    assert code == 0, err
    return json.loads(out)["life"]


def _point_ratings():
    """The planet–ring rating of `design` at each point's load, K_A = 1 (the way `life` sets a point)."""
    text = CONFIG.read_text()
    out = []
    for _, _, torque, speed in POINTS:
        _, d = design_of(text, (f"input.speed_rpm={speed!r}", f"load.torque_Nm={torque!r}",
                                "load.application_factor=1.0"))
        out.append(d.stages[0])
    return out


def test_ring_and_planet_ring_side_bins_by_hand():
    stage = _doc()["stages"][0]
    rated = _point_ratings()
    cases = [  # member, rating member of the planet–ring mesh, cycles per input rpm and hour, S–N nodes
        ("ring", "gear", 60.0 * N, {"pitting": ZNT, "bending": YNT_THROUGH}),
        ("planet_ring_side", "pinion", 60.0 * Z_R / Z_P, {"pitting": ZNT, "bending": YNT_CASE}),
    ]
    for member, rated_as, per_rpm_h, nodes in cases:
        for mode in ("pitting", "bending"):
            ml = stage[member][mode]
            assert len(ml["bins"]) == len(POINTS)  # one bin per duty point
            damage, below = 0.0, True
            for b, (name, hours, _, speed), st in zip(ml["bins"], POINTS, rated, strict=True):
                m = getattr(st.planetary.planet_ring.rating, rated_as)
                assert b["point"] == name
                assert_allclose(b["cycles"], hours * per_rpm_h * speed, rtol=1e-12)
                assert_allclose(b["force_N"], st.planetary.planet_ring.static_force_N.tangential, rtol=1e-12)
                stress = m.sigma_H_MPa if mode == "pitting" else m.sigma_F_MPa
                assert_allclose(b["stress_MPa"], stress, rtol=1e-12)
                endurance = m.sigma_HG_MPa / m.Z_NT if mode == "pitting" else m.sigma_FG_MPa / m.Y_NT
                n_f = _cycles_to_failure(stress / endurance, nodes[mode])
                assert_allclose(b["cycles_to_failure"], n_f, rtol=1e-9)
                damage += b["cycles"] / n_f
                below = below and stress / endurance < nodes[mode][-1][1]  # under the curve's last node (1e10)
            assert_allclose(ml["damage"], damage, rtol=1e-9)
            assert ml["below_endurance"] == below
            if below:  # every class under the endurance limit: an infinite life (docs/life.md)
                assert ml["life_h"] is None
            else:
                assert_allclose(ml["life_h"], HOURS / damage, rtol=1e-9)


def test_the_ring_is_the_critical_member_and_its_flank_fails_within_the_duty():
    """The reference stage's ring (through-hardened, S_H 0.861 at K_A 1.25 in `design`) has the shortest life of
    every member and mode, shorter than the duty (D > 1), by pitting."""
    stage = _doc()["stages"][0]
    lives = {(m, mode): stage[m][mode]["life_h"] for m in ("pinion", "gear", "ring", "planet_ring_side")
             for mode in ("pitting", "bending")}
    assert min(lives, key=lambda k: math.inf if lives[k] is None else lives[k]) == ("ring", "pitting")
    assert stage["ring"]["pitting"]["damage"] > 1.0 and lives[("ring", "pitting")] < HOURS


def test_the_sun_planet_members_are_unchanged_and_the_planet_root_sums_both_meshes():
    """pinion (sun) and gear (planet) stay the sun–planet mesh's (its rating's stresses, the sun's N contacts);
    the planet's root over both meshes is the conservative Miner sum of its sun-mesh and ring-mesh bending."""
    stage = _doc()["stages"][0]
    rated = _point_ratings()
    for b, (_, hours, _, speed), st in zip(stage["gear"]["bending"]["bins"], POINTS, rated, strict=True):
        assert_allclose(b["stress_MPa"], st.rating.gear.sigma_F_MPa, rtol=1e-12)
        assert_allclose(b["cycles"], hours * 60.0 * speed * Z_R / Z_P, rtol=1e-12)
    for b, (_, hours, _, speed), st in zip(stage["pinion"]["pitting"]["bins"], POINTS, rated, strict=True):
        assert_allclose(b["stress_MPa"], st.rating.pinion.sigma_H_MPa, rtol=1e-12)
        assert_allclose(b["cycles"], hours * 60.0 * speed * Z_R / Z_S * N, rtol=1e-12)
    root = stage["planet_root"]["bending"]
    total = stage["gear"]["bending"]["damage"] + stage["planet_ring_side"]["bending"]["damage"]
    assert_allclose(root["damage"], total, rtol=1e-12)
    if root["below_endurance"]:  # both meshes' root stresses under the endurance limit: infinite
        assert root["life_h"] is None and stage["gear"]["bending"]["below_endurance"]
    else:
        assert_allclose(root["life_h"], HOURS / total, rtol=1e-12)
    assert len(root["bins"]) == 2 * len(POINTS)
    assert set(stage) == {"index", "pinion", "gear", "ring", "planet_ring_side", "planet_root", "sun", "planet"}


def test_csv_and_tables_name_the_ring_mesh_members():
    code, out, err = _run("--static", "--format", "csv")
    assert code == 0, err
    rows = out.splitlines()
    members = {r.split(",")[1] for r in rows[1:]}
    assert members == {"pinion", "gear", "ring", "planet_ring_side", "planet_root"}
    assert rows[0].split(",")[:3] == ["stage", "member", "mode"]
    code, out, err = _run("--static", "--format", "table")
    assert code == 0, err
    assert "stage 1 ring: load spectrum" in out and "stage 1 planet (ring mesh): load spectrum" in out
    assert "planet root (both meshes)" in out


def test_a_ring_without_flank_roughness_is_refused_naming_the_key(tmp_path):
    text = CONFIG.read_text().replace("flank_roughness_Rz_um = 8, ", "")
    assert text != CONFIG.read_text()
    path = tmp_path / "no_ring_roughness.toml"
    path.write_text(text)
    res = CliRunner().invoke(cli, ["life", str(path), "--static", "-q"])
    assert res.exit_code == 2, res.output
    assert f"{path}: stage[0].ring.flank_roughness_Rz_um:" in res.stderr and "Traceback" not in res.stderr


def test_a_turning_ring_counts_its_speed_relative_to_the_carrier(tmp_path):
    """Carrier held, the sun driving (a star stage): the ring turns at n_s z_s / z_r, the planet at n_s z_s / z_p
    (both relative to the carrier, which is still); a ring tooth meets N planets per turn."""
    text = CONFIG.read_text().replace('fixed = "ring"', 'fixed = "carrier"').replace('input = "carrier"', 'input = "sun"')
    path = tmp_path / "star.toml"
    path.write_text(text)
    res = CliRunner().invoke(cli, ["life", str(path), "--static", "--format", "json", "-q"])
    assert res.exit_code == 0, res.output
    stage = json.loads(res.stdout)["life"]["stages"][0]
    for (_, hours, _, speed), ring, side in zip(POINTS, stage["ring"]["bending"]["bins"],
                                                stage["planet_ring_side"]["pitting"]["bins"], strict=True):
        assert_allclose(ring["cycles"], hours * 60.0 * speed * Z_S / Z_R * N, rtol=1e-12)
        assert_allclose(side["cycles"], hours * 60.0 * speed * Z_S / Z_P, rtol=1e-12)


def test_the_ring_spectrum_safety_makes_the_damage_one():
    """Scaling every force by the safety s (sigma_H by sqrt(s)) gives D = 1 on the hand-inverted curve."""
    ml = _doc()["stages"][0]["ring"]["pitting"]
    s = ml["safety"]
    assert s < 1.0  # D > 1 at s = 1
    d = sum(b["cycles"] / _cycles_to_failure(b["stress_MPa"] * math.sqrt(s) / b["endurance_MPa"], ZNT)
            for b in ml["bins"])
    assert_allclose(d, 1.0, rtol=1e-8)


def test_the_contract_names_sun_planet_and_ring():
    """DESIGN §10 names a planetary stage's members ``sun``, ``planet``, ``ring``: ``sun`` is the sun–planet mesh's
    sun, counted by hand (hours × 60 × |n_s − n_c| × N, n_s − n_c = n_c z_r / z_s by Willis); ``planet`` takes
    the more damaged of the planet's two flanks (the sun drives one, the ring reacts on the other) and the
    root bending of both meshes summed on the same root."""
    st = _doc()["stages"][0]
    assert st["sun"] == st["pinion"]
    cycles = [b["cycles"] for b in st["sun"]["pitting"]["bins"]]
    assert_allclose(cycles, [h * 60 * n * Z_R / Z_S * N for _, h, _, n in POINTS], rtol=1e-12)
    flanks = {"sun_mesh": st["gear"]["pitting"], "ring_mesh": st["planet_ring_side"]["pitting"]}
    worst = max(flanks, key=lambda k: flanks[k]["damage"])
    planet = st["planet"]
    assert planet["pitting"]["flank"] == worst
    assert planet["pitting"]["damage"] == flanks[worst]["damage"]
    assert planet["pitting"]["bins"] == flanks[worst]["bins"]
    assert planet["bending"] == st["planet_root"]["bending"]
    both = st["gear"]["bending"]["damage"] + st["planet_ring_side"]["bending"]["damage"]
    assert_allclose(planet["bending"]["damage"], both, rtol=1e-12)  # the planet root's Miner sum over both meshes
