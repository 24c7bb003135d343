"""design and life say the same of a bearing (docs/bearings.md), every figure against a hand calculation:

- an unloaded bearing (the gears at one bearing's position: by moments about it the other carries nothing) has
  no a_ISO in either (ISO 281's e_C C_u / P is not defined at P = 0; its lives are unbounded, null), and warns of
  no kappa below 0.1 (there is no a_ISO to take at 0.1);
- kappa below ISO 281's range warns once per bearing over the duty, naming the duty points below it (kappa =
  nu / nu_1 at each point's speed, ASTM D341 for nu), not once per point and again over the duty;
- design warns ``bearing_life_short`` at its load when L10_h = 1e6 (C/P)^p / (60 n) is below [rating]
  required_life_h, with life's data keys; life does not repeat it per duty point.
"""

from __future__ import annotations

from numpy.testing import assert_allclose

from tests.life.test_bearing_iso281_scenes import BEARINGS, RATIO, SLOW, SPUR, _json, _nu, _nu1, _spur_point

KAPPA = "bearing_kappa_below_range"
SHORT = "bearing_life_short"


def _codes(doc: dict, code: str) -> list[dict]:
    return [w for w in doc["warnings"] if w["code"] == code]


def test_an_unloaded_bearing_has_no_a_iso_in_design_nor_in_life(tmp_path):
    """Both gears at x = 0, on the first bearing of each shaft: the bearings at x = 120 mm carry nothing
    (sum of moments about x = 0), the others the whole tooth force sqrt(F_t^2 + F_r^2). design's a_ISO was the
    clamp 50 for them, life's null: both null now, as their L10 and L_nm; the loaded ones keep ISO 281's a_ISO.
    The thin hot oil puts every kappa below 0.1: only the loaded bearings warn."""
    text = SLOW.replace("axial_position_mm = 60", "axial_position_mm = 0").replace("helix_angle_deg = 15",
                                                                                 "helix_angle_deg = 0")
    design = _json(tmp_path, "design", text)
    hand = _spur_point(400, 100)
    for j, b in enumerate(design["bearings"]):
        if j % 2:  # the bearings at x = 120 mm
            assert b["equivalent_load_N"] == 0.0
            assert b["a_ISO"] is None and b["L10_h"] is None and b["L_nm_h"] is None, b
        else:
            assert_allclose(b["equivalent_load_N"], 2 * hand[j]["equivalent_load_N"], rtol=1e-9)
            assert b["a_ISO"] is not None and 0 < b["a_ISO"] < 50
        assert_allclose(b["kappa"], _nu(90, 10, 2.7) / _nu1(b["speed_rpm"], BEARINGS[j][3]), rtol=1e-12)
    assert [w["bearing"] for w in _codes(design, KAPPA)] == [1, 3]
    life = _json(tmp_path, "life", text, "--static")
    for j, b in enumerate(life["life"]["bearings"]):
        if j % 2:
            assert b["a_ISO"] is None and b["a_ISO_points"] == [None, None] and b["L_nm_h"] is None, b
        else:
            assert None not in b["a_ISO_points"] and b["a_ISO"] is not None
    assert sorted(w["bearing"] for w in _codes(life, KAPPA)) == [1, 3]


def test_kappa_below_the_range_is_said_once_per_bearing_naming_the_points(tmp_path):
    """The base file at 1500 r/min (kappa in range), its duty points at 100 and 50 r/min on the thin oil: both
    below 0.1 on every bearing. One warning per bearing (it was one per point and one over the duty: 12 for 4
    bearings), the lowest kappa (the 50 r/min point's, by hand) and both points named."""
    text = SLOW.replace("[input]\nspeed_rpm = 100", "[input]\nspeed_rpm = 1500").replace("speed_rpm = 6000",
                                                                                        "speed_rpm = 50")
    life = _json(tmp_path, "life", text, "--static")
    said = _codes(life, KAPPA)
    assert [w["bearing"] for w in said] == [1, 2, 3, 4], said
    nu = _nu(90, 10, 2.7)
    for j, w in enumerate(said):
        n = 50.0 if j < 2 else 50.0 / RATIO
        assert_allclose(w["kappa"], nu / _nu1(n, BEARINGS[j][3]), rtol=1e-12)
        assert w["points"] == ["full", "light"]
        assert "duty points full, light" in w["message"] and not w["message"].startswith("duty point")
    # one point below the range (50 r/min), the other (6000 r/min) in it: that point alone is named
    text = text.replace("speed_rpm = 100\n[[duty]]", "speed_rpm = 6000\n[[duty]]")
    said = _codes(_json(tmp_path, "life", text, "--static"), KAPPA)
    assert len(said) == 4 and all(w["points"] == ["light"] for w in said), said
    assert all(nu / _nu1(6000 if j < 2 else 6000 / RATIO, BEARINGS[j][3]) > 0.1 for j in range(4))


def test_design_warns_a_bearing_life_shorter_than_required(tmp_path):
    """Scene A without the modified-life keys: L10_h = 1e6 (C/P)^p / (60 n) by hand, the reaction half the tooth
    force. The balls' (about 30300 h) are below required_life_h = 50000 h, the rollers' (about 1.2e7 h) above: two
    warnings with life's code and data keys; at 30000 h none. life carries the base file's two and repeats
    them for no duty point, although the full-load point's own design is short too (the duty's verdict is its own, over all the points)."""
    text = SPUR.replace("required_life_h = 8000", "required_life_h = 50000")
    for key in ("fatigue_load_limit_kN = 0.8\n", "fatigue_load_limit_kN = 12.9\n", "pitch_diameter_mm = 60\n",
                "pitch_diameter_mm = 85\n", "reliability_percent = 99\n"):
        text = text.replace(key, "")
    hand = _spur_point(400, 1500)
    l10_h = [1e6 * (BEARINGS[j][0] / h["equivalent_load_N"]) ** (3.0 if j < 2 else 10 / 3) / (60 * h["speed_rpm"])
             for j, h in enumerate(hand)]
    assert 30000 < l10_h[0] < 50000 < l10_h[2]
    design = _json(tmp_path, "design", text)
    short = _codes(design, SHORT)
    assert [w["bearing"] for w in short] == [1, 2], short
    for w in short:
        assert set(w) - {"code", "message"} == {"stage", "bearing", "life", "life_h", "hours", "required_life_h",
                                                   "required_dynamic_load_rating_kN"}
        assert w["stage"] is None  # no stage's: null, as every warning about the train (docs/output.md)
        assert w["life"] == "L10" and w["required_life_h"] == 50000 and w["hours"] is None
        assert_allclose(w["life_h"], l10_h[w["bearing"] - 1], rtol=1e-9)
        assert "at the design load is shorter than the required 50000 h ([rating] required_life_h)" in w["message"]
    assert not _codes(_json(tmp_path, "design", text.replace("required_life_h = 50000", "required_life_h = 30000")),
                      SHORT)
    # the full-load point at 420 N·m (its own design below 50000 h too, 30300 (400/420)^3 h): not said per point
    life = _json(tmp_path, "life", text.replace('hours = 2000\ntorque_Nm = 400', 'hours = 2000\ntorque_Nm = 420'),
                 "--static")
    at_design = [w for w in _codes(life, SHORT) if "at the design load" in w["message"]]
    assert [w["message"] for w in at_design] == [w["message"] for w in short]
    assert not [w for w in _codes(life, SHORT) if "point" in w], life["warnings"]
