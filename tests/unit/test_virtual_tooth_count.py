"""``[rating] virtual_tooth_count``: the z_n of method B's load angle γ_e (ISO 6336-3:2006, 6.2), ISO's
z/(cos² β_b cos β) by default or the classical z/cos³ β (docs/iso6336.md, "The virtual tooth count in the load
angle"). By hand: only γ_e changes, α_Fen = α_en − γ_e moves by exactly the difference in γ_e."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest
from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli
from gearcli.design import rating_root as rr

AN = math.radians(20.0)
ROOT = Path(__file__).resolve().parents[2]


def test_the_two_counts_by_hand():
    beta = math.radians(10.0)
    beta_b = math.atan(math.tan(beta) * math.cos(math.atan(math.tan(AN) / math.cos(beta))))
    # cos 10° = 0.98480775, cos³ = 0.95511217: 24/0.95511217 = 25.1279 (the report's γ_e); β_b = 9.391°:
    # 24/(cos² 9.391° · cos 10°) = 24/(0.97358 · 0.98481) = 25.037 (the report's printed zn)
    assert_allclose(rr.load_angle_teeth(24, beta, beta_b, "cos3"), 25.1279, atol=5e-5)
    assert_allclose(rr.load_angle_teeth(24, beta, beta_b, "iso"), 25.037, atol=5e-4)
    assert_allclose(rr.load_angle_teeth(-95, beta, beta_b, "cos3"), -95 / math.cos(beta) ** 3, rtol=1e-15)
    with pytest.raises(ValueError, match="virtual_tooth_count"):
        rr.load_angle_teeth(24, beta, beta_b, "cos2")


@pytest.mark.parametrize("internal", [False, True])
@pytest.mark.parametrize("beta_deg", [0.0, 10.0, 25.0])
def test_only_the_load_angle_moves(internal, beta_deg):
    """Δα_Fen = −Δγ_e = −(π/2 + 2 x tan α_n)(1/z_c − 1/z_n), the signed counts (a ring's z_n < 0); s_Fn, ρ_F, q_s
    and d_en are untouched; on a spur gear (β = 0) both counts are z and the forms are identical."""
    beta = math.radians(beta_deg)
    beta_b = math.atan(math.tan(beta) * math.cos(math.atan(math.tan(AN) / math.cos(beta))))
    m, rack = 4.0, (1.25, 0.38)
    if internal:
        z, x = 71, -0.2
        d = z * m / math.cos(beta)
        args = (z, m, AN, beta, beta_b, x, d - 2 * m * (1 + x), d, 1.6, rack)
        iso, cos3 = rr.internal_tooth_form(*args), rr.internal_tooth_form(*args, virtual_tooth_count="cos3")
        sign = -1
    else:
        z, x = 23, 0.3
        d = z * m / math.cos(beta)
        args = (z, m, AN, beta, beta_b, x, d + 2 * m * (1 + x), d, 1.55, rack)
        iso, cos3 = rr.tooth_form(*args), rr.tooth_form(*args, virtual_tooth_count="cos3")
        sign = 1
    z_n = sign * z / (math.cos(beta_b) ** 2 * math.cos(beta))
    z_c = sign * z / math.cos(beta) ** 3
    d_gamma = (math.pi / 2 + 2 * x * math.tan(AN)) * (1 / z_c - 1 / z_n)
    assert_allclose(cos3["alpha_Fen"] - iso["alpha_Fen"], -d_gamma, atol=1e-13)
    for key in ("s_Fn", "rho_F", "q_s", "d_en"):
        assert cos3[key] == iso[key]
    if beta_deg == 0.0:
        assert cos3 == iso
    else:
        assert cos3["Y_F"] != iso["Y_F"]


def _design(extra: str):
    text = (ROOT / "configs" / "wind_turbine_allowances.toml").read_text()
    text = text.replace('virtual_tooth_count = "cos3"', extra)
    path = ROOT / "tests" / "unit" / "_virtual_tooth_count_tmp.toml"
    try:
        path.write_text(text)
        return CliRunner().invoke(cli, ["design", str(path), "--format", "json"])
    finally:
        path.unlink(missing_ok=True)


def test_absent_is_iso_and_a_bad_value_exits_2_naming_the_key():
    absent, iso = _design(""), _design('virtual_tooth_count = "iso"')
    assert absent.exit_code == iso.exit_code == 0
    # everything but the provenance block (the input file's hash) is equal
    a, b = json.loads(absent.stdout), json.loads(iso.stdout)
    assert {k: v for k, v in a.items() if k != "input_sha256"} == {k: v for k, v in b.items() if k != "input_sha256"}
    assert not any(w["code"] == "rating_not_iso" for w in a["warnings"])
    cos3 = _design('virtual_tooth_count = "cos3"')
    assert cos3.exit_code == 0
    (w,) = [w for w in json.loads(cos3.stdout)["warnings"] if w["code"] == "rating_not_iso"]
    assert "cos³" in w["message"] and w["value"] == "cos3"
    bad = _design('virtual_tooth_count = "z3"')
    assert bad.exit_code == 2
    assert "rating.virtual_tooth_count" in bad.output and "Traceback" not in bad.output
