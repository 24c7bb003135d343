"""The default mesh law, calibrated to ISO 6336-1 at the operating point (DESIGN section 13, issue 30 item 1).

``stiffness = "iso6336"`` calibrates the tangent: e K h0^(e-1) = k_n = c_γα b / cos² β_b at the static normal load
F_n = K h0^e, for any exponent; an omitted ``[contact]`` is that law with e = 1.5 and viscous damping_ratio 0.05.
Hand calculations below use the stage's geometry written out (r_b = z m_n / (2 cos β) cos α_t, F_n = T / (r cos α_n
cos β)) and ISO's c_γα from the design (itself checked by hand in tests/reference/test_design_seed.py).
"""

from __future__ import annotations

import copy
import json
import math
import tomllib
from pathlib import Path

import pytest
from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli import api
from gearcli.cli import cli
from gearcli.config.schema import DesignFile
from gearcli.design import compute_design, contact_stiffness_N_mm_e

ROOT = Path(__file__).resolve().parents[2]
CONFIGS = sorted((ROOT / "configs").glob("*.toml"))

# one helical stage, torque-driven (both bodies free), inertias given: m_n 4, z 19/74, beta 12°, b = 70 mm
STAGE = {"normal_module_mm": 4.0, "helix_angle_deg": 12.0,
         "pinion": {"teeth": 19, "face_width_mm": 75.0, "hand": "left", "inertia_kg_m2": 0.02},
         "gear": {"teeth": 74, "face_width_mm": 70.0, "hand": "right", "inertia_kg_m2": 0.6}}
ONE_STAGE = {"stage": [STAGE], "input": {"speed_rpm": 1480.0, "drive": "torque", "torque_Nm": 300.0},
             "load": {"torque_Nm": 300.0 * 74 / 19}}


def _validated(doc: dict) -> tuple[DesignFile, object]:
    cfg = DesignFile.model_validate(doc)
    return cfg, compute_design(cfg)


def _hand_stage(torque_Nm: float) -> dict[str, float]:
    """Base radii (m), F_n (N) and cos² β_b of ``STAGE`` by hand."""
    beta, alpha_n = math.radians(12.0), math.radians(20.0)
    alpha_t = math.atan(math.tan(alpha_n) / math.cos(beta))  # 20.41031°
    beta_b = math.atan(math.tan(beta) * math.cos(alpha_t))  # 11.26652°
    r = [z * 4.0 / (2 * math.cos(beta)) for z in (19, 74)]  # pitch radii, mm
    return {"r_bp": r[0] * math.cos(alpha_t) / 1000, "r_bg": r[1] * math.cos(alpha_t) / 1000,
            "F_n": torque_Nm * 1000 / r[0] / (math.cos(alpha_n) * math.cos(beta)), "cos2_bb": math.cos(beta_b) ** 2}


def test_an_omitted_contact_table_is_the_calibrated_law():
    cfg, _ = _validated(copy.deepcopy(ONE_STAGE))
    law = cfg.contact_for(0)
    assert (law.stiffness, law.exponent, law.damping_ratio) == ("iso6336", 1.5, 0.05)
    assert not law.impact_damping


def test_impact_damping_where_a_file_gives_its_keys():
    # the seed's law by name: stiffness "hertz" with its damping keys (no damping_ratio) damps by the IMPACT ramp
    doc = {**copy.deepcopy(ONE_STAGE), "contact": {"stiffness": "hertz", "damping_Ns_mm": 50.0,
                                                   "full_damping_penetration_mm": 0.1}}
    assert _validated(doc)[0].contact_for(0).damping_ratio is None
    # one IMPACT key in a stage's mesh makes that mesh IMPACT-damped (its other key at the seed's 0.1 mm)
    doc = copy.deepcopy(ONE_STAGE)
    doc["stage"][0]["mesh"] = {"damping_Ns_mm": 20.0}
    law = _validated(doc)[0].contact_for(0)
    assert law.damping_ratio is None and law.damping_Ns_mm == 20.0 and law.full_damping_penetration_mm == 0.1
    # a damping_ratio given anywhere wins, as before
    doc["contact"] = {"damping_ratio": 0.08}
    assert _validated(doc)[0].contact_for(0).damping_ratio == 0.08


@pytest.mark.parametrize("exponent", [1.0, 1.5, 2.2])
def test_iso6336_calibrates_the_tangent_by_hand(exponent):
    doc = {**copy.deepcopy(ONE_STAGE), "contact": {"stiffness": "iso6336", "exponent": exponent}}
    cfg, r = _validated(doc)
    st = r.stages[0]
    h = _hand_stage(300.0)
    # k_n = c_γα b / cos² β_b, b = 70 mm (the smaller face), N/mm
    k_n = st.iso6336_mesh_stiffness_N_mm_um * 70.0 * 1000.0 / h["cos2_bb"]
    assert_allclose(st.static_force_N.normal, h["F_n"], rtol=1e-12)
    K = contact_stiffness_N_mm_e(st, cfg.contact_for(0))
    h0 = (h["F_n"] / K) ** (1.0 / exponent)  # F_n = K h0^e
    assert_allclose(exponent * K * h0 ** (exponent - 1.0), k_n, rtol=1e-12)  # the tangent is ISO's
    assert_allclose(h0, exponent * h["F_n"] / k_n, rtol=1e-12)  # e times ISO's static deflection
    ms = st.mesh_stiffness
    assert ms.law == "iso6336"
    assert_allclose([ms.K, ms.linearised_N_mm, ms.iso_N_mm, ms.static_approach_mm], [K, k_n, k_n, h0], rtol=1e-12)
    assert not [d for d in r.diagnostics if d.code == "stiffness_not_iso"]


def test_single_mesh_mode_is_the_closed_form():
    # free-free pair: omega^2 = k_t (r_bp^2 / J_p + r_bg^2 / J_g), k_t = c_γα b along the transverse line of action
    cfg, r = _validated(copy.deepcopy(ONE_STAGE))
    h = _hand_stage(300.0)
    k_t = r.stages[0].iso6336_mesh_stiffness_N_mm_um * 70.0 * 1e6  # N/(mm um) x mm = N/um = 1e6 N/m
    mobility = h["r_bp"] ** 2 / 0.02 + h["r_bg"] ** 2 / 0.6
    free = {a.boundary: a for a in api.modes(cfg, r)}["free"]
    (mode,) = [m for m in free.modes if not m.rigid]
    assert_allclose(mode.frequency_Hz, math.sqrt(k_t * mobility) / (2 * math.pi), rtol=1e-9)
    # viscous c = 2 zeta sqrt(k_lin m_e) on the transverse DTE, m_e = 1 / mobility, k_lin the normal slope k_n
    # (DESIGN section 6: "K itself when the exponent is 1"): against the transverse k_t = k_n cos² β_b the mode has
    # zeta sqrt(k_n / k_t) = 0.05 / cos β_b = 0.05 / 0.980729 = 0.0509826
    assert_allclose(mode.damping_ratio, 0.05 / math.sqrt(h["cos2_bb"]), rtol=1e-9)
    # held pinion (a speed drive's boundary): the gear alone on the mesh, omega^2 = k_t r_bg^2 / J_g
    clamped = {a.boundary: a for a in api.modes(cfg, r)}["clamped_input"]
    assert_allclose(clamped.modes[0].frequency_Hz, math.sqrt(k_t * h["r_bg"] ** 2 / 0.6) / (2 * math.pi), rtol=1e-9)


def _without_law(path: Path) -> dict:
    doc = tomllib.loads(path.read_text())
    doc.pop("contact", None)
    for st in doc["stage"]:
        st.pop("mesh", None)
    return doc


@pytest.mark.parametrize("path", CONFIGS, ids=lambda p: p.stem)
def test_default_law_modes_equal_the_linear_iso_model(path):
    """Acceptance: without [contact], every mode (both boundaries) is the linear ISO model's within 1e-3."""
    default = _validated(_without_law(path))
    linear = _validated({**_without_law(path), "contact": {"stiffness": "iso6336", "exponent": 1.0}})
    for a, b in zip(api.modes(*default), api.modes(*linear), strict=True):
        for m, n in zip(a.modes, b.modes, strict=True):
            assert m.rigid == n.rigid
            assert_allclose(m.frequency_Hz, n.frequency_Hz, rtol=1e-3, err_msg=f"{a.boundary} mode {m.number}")


def test_each_duty_point_calibrates_at_its_own_load():
    """planetary_duty has no [contact]: every duty point's design has the ISO tangent at its own static load, and
    the model integrates that point's K."""
    session = api.prepare_life(str(ROOT / "configs" / "planetary_duty.toml"))
    ks = []
    for p in session.points:
        case = api.design_case(session.scene, p.overrides())
        spec = api.model_spec(case.cfg, case.design)
        for st, mesh in zip(case.design.stages, spec.meshes, strict=True):
            laws = [st.mesh_stiffness] + ([st.planetary.planet_ring.mesh_stiffness] if st.planetary else [])
            for law in laws:
                assert_allclose(law.linearised_N_mm, law.iso_N_mm, rtol=1e-12)
            assert_allclose(mesh.stiffness_N_m_e, st.mesh_stiffness.K * 1000.0 ** 1.5, rtol=1e-12)
        ks.append(case.design.stages[0].mesh_stiffness.K)
    assert len(set(ks)) == len(ks)  # three loads, three coefficients


def test_design_modes_and_simulate_json_report_the_law_and_warn_off_iso(tmp_path):
    doc = {**copy.deepcopy(ONE_STAGE), "simulation": {"duration_s": 0.05, "steps": 100}}
    path = tmp_path / "pair.toml"
    import tomli_w

    path.write_text(tomli_w.dumps(doc))
    runner = CliRunner()
    keys = {"law", "K", "exponent", "linearised_N_mm", "iso_N_mm"}
    for cmd, get in (("design", lambda d: d["stages"][0]["mesh_stiffness"]),
                     ("modes", lambda d: d["meshes"][0]["mesh_stiffness"]),
                     ("simulate", lambda d: d["summary"]["stages"][0]["mesh_stiffness"])):
        for law, warned in (([], False), (["--set", "contact.stiffness=hertz"], True)):
            out = runner.invoke(cli, [cmd, str(path), "--format", "json", *law])
            assert out.exit_code == 0, out.output
            d = json.loads(out.stdout)
            ms = get(d)
            assert keys <= set(ms)
            codes = [w for w in d["warnings"] if w["code"] == "stiffness_not_iso"]
            if not warned:
                assert ms["law"] == "iso6336" and not codes
                assert_allclose(ms["linearised_N_mm"], ms["iso_N_mm"], rtol=1e-6)  # simulate: its own static load
            else:
                # the point-contact Hertz law: k_lin = 1.5 K_hertz h0^0.5 with h0 = (F_n / K_hertz)^(2/3)
                assert ms["law"] == "hertz" and len(codes) == 1
                w = codes[0]
                assert_allclose([w["linearised_N_mm"], w["iso_N_mm"]], [ms["linearised_N_mm"], ms["iso_N_mm"]],
                                rtol=1e-6)
                assert abs(w["linearised_N_mm"] / w["iso_N_mm"] - 1) > 0.25
                assert f"{w['iso_N_mm']:.4g}" in w["message"] and f"{w['linearised_N_mm']:.4g}" in w["message"]


def test_planet_meshes_linearise_to_their_own_iso_stiffness():
    """planetary_stage has no [contact]: every planet's sun mesh and ring mesh is linearised at k_n cos² β_b of its
    own ISO stiffness (sun–planet and planet–ring c_γα, face width, static force), transverse, N/m."""
    cfg = DesignFile.model_validate(tomllib.loads((ROOT / "configs" / "planetary_stage.toml").read_text()))
    design = compute_design(cfg)
    st = design.stages[0]
    cos2_bb = math.cos(math.radians(st.base_helix_angle_deg)) ** 2
    for mesh, law in (("sun", st.mesh_stiffness), ("ring", st.planetary.planet_ring.mesh_stiffness)):
        face = st.face_width_mm if mesh == "sun" else st.planetary.planet_ring.face_width_mm
        c_ga = st.iso6336_mesh_stiffness_N_mm_um if mesh == "sun" else \
            st.planetary.planet_ring.iso6336_mesh_stiffness_N_mm_um
        assert_allclose(law.iso_N_mm, c_ga * face * 1000.0 / cos2_bb, rtol=1e-12)
        for a in api.modes(cfg, design):
            k = [s for c, s in zip(a.connectors, a.stiffness, strict=True) if c.endswith(f"{mesh} mesh")]
            assert len(k) == st.planetary.planet_count
            assert_allclose(k, law.iso_N_mm * 1000.0 * cos2_bb, rtol=1e-9)
