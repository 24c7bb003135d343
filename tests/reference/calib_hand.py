"""Scenes and hand calculations of the calibrated-mesh-law reference tests (tests/reference/test_calibrated_law_engineer.py,
tests/reference/test_calibrated_law_cli.py); the formulas are written out in the first one's module text."""

from __future__ import annotations

import copy
import json
import math

import numpy as np
import scipy.optimize
import tomli_w
from click.testing import CliRunner

from gearcli.cli import cli
from gearcli.config.schema import DesignFile
from gearcli.design import compute_design

RPM = 2 * math.pi / 60
STEEL = {"density_kg_m3": 7850.0, "youngs_modulus_MPa": 2.1e5, "poisson_ratio": 0.3}
Q_COEF = (0.04723, 0.15551, 0.25791)  # ISO 6336-1 C1, C2, C3 (x = 0)


def _stage(m_n, beta, z1, z2, b1, b2, j1, j2, alpha_n=20.0, mesh=None, shaft=None):
    hands = ({"hand": "left"}, {"hand": "right"}) if beta else ({}, {})
    st = {"normal_module_mm": m_n, "normal_pressure_angle_deg": alpha_n, "helix_angle_deg": beta,
          "pinion": {"teeth": z1, "face_width_mm": b1, "material": "steel", "inertia_kg_m2": j1, **hands[0]},
          "gear": {"teeth": z2, "face_width_mm": b2, "material": "steel", "inertia_kg_m2": j2, **hands[1]}}
    if mesh:
        st["mesh"] = mesh
    if shaft:
        st["shaft"] = shaft
    return st


# -------------------------------------------------------------------------------------------- the scenes
# two helical stages behind a speed drive, no [contact]: the default law (iso6336, e = 1.5, zeta = 0.05)
TWO_HELICAL = {
    "materials": {"steel": STEEL},
    "stage": [_stage(4.0, 15.0, 23, 71, 60.0, 55.0, 0.012, 0.45), _stage(6.0, 9.0, 19, 62, 90.0, 85.0, 0.05, 2.4,
                                                                          alpha_n=22.5)],
    "input": {"speed_rpm": 1480.0, "ramp_s": 0.05},
    "load": {"torque_Nm": 4000.0, "ramp_s": 0.05},
}
# three stages (helical, spur, helical), a table motor on a coupling, a drum on a coupling with a quadratic (fan)
# law, [contact] e = 1.3, stage 1 IMPACT-damped (30 N s/mm at 5 um: its STEP ramp at the static approach), stage 2
# overridden to Hertz e = 2.0, stage 3 to iso6336 e = 2.5 with zeta = 0.08
THREE_MIXED = {
    "materials": {"steel": STEEL},
    "contact": {"exponent": 1.3},
    "stage": [_stage(3.0, 12.0, 21, 67, 45.0, 40.0, 0.004, 0.16,
                     mesh={"damping_Ns_mm": 30.0, "full_damping_penetration_mm": 0.005}),
              _stage(5.0, 0.0, 18, 59, 70.0, 65.0, 0.03, 1.1, mesh={"stiffness": "hertz", "exponent": 2.0}),
              _stage(8.0, 20.0, 17, 53, 110.0, 100.0, 0.2, 9.0,
                     mesh={"stiffness": "iso6336", "exponent": 2.5, "damping_ratio": 0.08})],
    "input": {"speed_rpm": 1470.0, "drive": "motor", "inertia_kg_m2": 0.6, "coupling_stiffness_Nm_rad": 4.0e4,
              "coupling_damping_Nms_rad": 3.0,
              "motor": {"torque_speed": [[0.0, 400.0], [1300.0, 450.0], [1450.0, 250.0], [1500.0, 0.0]]}},
    "load": {"torque_Nm": 2500.0, "speed_exponent": 2, "inertia_kg_m2": 60.0, "coupling_stiffness_Nm_rad": 2.0e6,
             "coupling_damping_Nms_rad": 40.0},
}
# one spur stage, exponent 1.0, torque drive, a tiny load (F_t / b far below 1 N/mm: the floor)
TINY_SPUR = {
    "materials": {"steel": STEEL},
    "contact": {"exponent": 1.0},
    "stage": [_stage(2.0, 0.0, 25, 40, 20.0, 20.0, 2.0e-4, 1.0e-3)],
    "input": {"speed_rpm": 3000.0, "drive": "torque", "torque_Nm": 0.005},
    "load": {"torque_Nm": 0.008},
}
# one helical stage, a huge load (F_t / b ~ 3000 N/mm), exponent 2.5, speed drive
HUGE_HELICAL = {
    "materials": {"steel": STEEL},
    "contact": {"stiffness": "iso6336", "exponent": 2.5, "damping_ratio": 0.03},
    "stage": [_stage(20.0, 10.0, 20, 61, 300.0, 290.0, 40.0, 2500.0)],
    "input": {"speed_rpm": 300.0},
    "load": {"torque_Nm": 2.5e6},
}
# the two helical stages behind a speed-driven motor on a coupling (the pinion shaft is free: its mesh's m_e has both
# sides) and a drum on a linear (speed_exponent 1) law, [contact] exponent 2.0 with the default damping
COUPLED_SPEED = {**copy.deepcopy(TWO_HELICAL), "contact": {"exponent": 2.0},
                 "input": {"speed_rpm": 1480.0, "ramp_s": 0.05, "inertia_kg_m2": 0.3,
                           "coupling_stiffness_Nm_rad": 1.5e4, "coupling_damping_Nms_rad": 1.0},
                 "load": {"torque_Nm": 4000.0, "ramp_s": 0.05, "speed_exponent": 1, "inertia_kg_m2": 25.0,
                          "coupling_stiffness_Nm_rad": 8.0e5, "coupling_damping_Nms_rad": 20.0}}
# the two helical stages with losses (eta 0.97 and 0.95), forward and reversed (the load drives back), e = 1.3
LOSSY = {**copy.deepcopy(TWO_HELICAL), "contact": {"exponent": 1.3}}
for _st, _eta in zip(LOSSY["stage"], (0.97, 0.95), strict=True):
    _st["efficiency"] = _eta
LOSSY_REVERSED = {**copy.deepcopy(LOSSY), "load": {"torque_Nm": -4000.0, "ramp_s": 0.05}}
# the two helical stages against a load table (torque rising with speed: 3500 N m at 0.8 and 9000 N m at twice the
# nominal output speed, so 3500 + 5500 x 0.2 / 1.2 = 4416.7 N m at it): the static load is the table's torque at the
# nominal speed, not its largest
_N_OUT = 1480.0 / (71 / 23 * 62 / 19)
TABLE_LOAD = {**copy.deepcopy(TWO_HELICAL), "contact": {"exponent": 1.5},
              "load": {"ramp_s": 0.05, "torque_speed": [[0.0, 1000.0], [0.8 * _N_OUT, 3500.0],
                                                         [2 * _N_OUT, 9000.0]]}}
# a speed-driven variant of THREE_MIXED for the command line: [contact] e = 1.3, stage 2 Hertz e = 2.0, stage 3
# iso6336 e = 2.5 (zeta 0.08), the drum on its coupling with a constant torque
THREE_SPEED = {**copy.deepcopy(THREE_MIXED),
               "input": {"speed_rpm": 1470.0, "ramp_s": 0.02},
               "load": {"torque_Nm": 2500.0, "ramp_s": 0.02, "inertia_kg_m2": 60.0,
                        "coupling_stiffness_Nm_rad": 2.0e6, "coupling_damping_Nms_rad": 40.0},
               "simulation": {"duration_s": 0.06, "steps": 120}}
# THREE_SPEED with flexible shafts between the stages (the second undamped) and a torque drive
FLEXIBLE = copy.deepcopy(THREE_SPEED)
FLEXIBLE["stage"][0]["shaft"] = {"stiffness_Nm_rad": 3.0e5, "damping_Nms_rad": 2.0}
FLEXIBLE["stage"][1]["shaft"] = {"stiffness_Nm_rad": 1.2e6}
FLEXIBLE["input"] = {"speed_rpm": 1470.0, "drive": "torque", "torque_Nm": 2500.0 * 21 / 67 * 18 / 59 * 17 / 53}
SCENES = {"two_helical": TWO_HELICAL, "table_load": TABLE_LOAD, "flexible": FLEXIBLE, "lossy": LOSSY,
          "lossy_reversed": LOSSY_REVERSED, "coupled_speed": COUPLED_SPEED, "three_mixed": THREE_MIXED,
          "tiny_spur": TINY_SPUR, "huge_helical": HUGE_HELICAL}


# ------------------------------------------------------------------------------------- hand calculations
def _hand_mesh(st: dict, law: dict, pinion_torque_Nmm: float, load_scale: float = 1.0) -> dict:
    """Geometry, ISO 6336-1 k_n and the law's K and tangent of one parallel stage (module text); ``load_scale``:
    the law's tangent at that multiple of the static load, K still calibrated at the static load."""
    m_n, a_n, beta = st["normal_module_mm"], math.radians(st["normal_pressure_angle_deg"]), \
        math.radians(st["helix_angle_deg"])
    z1, z2 = st["pinion"]["teeth"], st["gear"]["teeth"]
    b = min(st["pinion"]["face_width_mm"], st["gear"]["face_width_mm"])
    m_t = m_n / math.cos(beta)
    a_t = math.atan(math.tan(a_n) / math.cos(beta))
    d1, d2 = z1 * m_t, z2 * m_t
    rb1, rb2 = d1 * math.cos(a_t) / 2, d2 * math.cos(a_t) / 2
    ra1, ra2 = d1 / 2 + m_n, d2 / 2 + m_n
    b_b = math.atan(math.tan(beta) * math.cos(a_t))
    eps_a = (math.sqrt(ra1**2 - rb1**2) + math.sqrt(ra2**2 - rb2**2) - (d1 + d2) / 2 * math.sin(a_t)) \
        / (math.pi * m_t * math.cos(a_t))
    f_t = pinion_torque_Nmm / (d1 / 2)
    f_t_ref = max(abs(f_t), 1.0 * b)  # ISO's stiffness and the calibration at >= 1 N/mm
    zn1, zn2 = (z / (math.cos(b_b) ** 2 * math.cos(beta)) for z in sorted((z1, z2)))
    q = Q_COEF[0] + Q_COEF[1] / zn1 + Q_COEF[2] / zn2
    c_b = (1 + 0.5 * (1.2 - 1.25)) * (1 - 0.02 * (20.0 - math.degrees(a_n)))
    c_single = 1 / q * 0.8 * 1.0 * c_b * math.cos(beta) * min(f_t_ref / b / 100.0, 1.0) ** 0.25
    c_ga = c_single * (0.75 * eps_a + 0.25)
    k_n = c_ga * b * 1000.0 / math.cos(b_b) ** 2  # N/mm
    f_n = abs(f_t) / (math.cos(a_n) * math.cos(beta))
    f_n_ref = f_t_ref / (math.cos(a_n) * math.cos(beta))
    e = law["exponent"]
    if law["stiffness"] == "iso6336":
        h0 = e * f_n_ref / k_n
        K = f_n_ref / h0**e
        k_lin = k_n * load_scale ** ((e - 1) / e)  # the tangent at the calibration load is k_n
    else:
        r_eq = (d1 / 2) * (d2 / 2) / (d1 / 2 + d2 / 2)
        e_star = 1 / (2 * (1 - STEEL["poisson_ratio"] ** 2) / STEEL["youngs_modulus_MPa"])
        K = 4 / 3 * math.sqrt(r_eq) * e_star if law["stiffness"] == "hertz" else float(law["stiffness"])
        h0 = (f_n / K) ** (1 / e)
        k_lin = e * K * (h0 * load_scale ** (1 / e)) ** (e - 1)
    # the static approach where the models linearise: at the load (times load_scale), an iso6336 law not below
    # its calibration load
    h_op = (max(f_n * load_scale, f_n_ref if law["stiffness"] == "iso6336" else 0.0) / K) ** (1 / e)
    return {"h_op_mm": h_op, "rb1": rb1 / 1000, "rb2": rb2 / 1000, "cos_bb": math.cos(b_b), "eps_a": eps_a, "c_single": c_single,
            "c_ga": c_ga, "k_n": k_n, "K": K, "h0_mm": h0, "k_lin": k_lin, "f_n": f_n, "f_t": f_t,
            "ratio": z2 / z1, "e": e}


IMPACT = ("damping_Ns_mm", "full_damping_penetration_mm")


def _law(doc: dict, k: int) -> dict:
    """Stage k's law: the defaults (iso6336, 1.5, zeta 0.05; IMPACT 50 N s/mm at 0.1 mm), [contact], its
    [stage.mesh]; an IMPACT key given without a damping_ratio anywhere makes it IMPACT-damped (DESIGN section 13)."""
    contact, mesh = doc.get("contact", {}), doc["stage"][k].get("mesh", {})
    law = {"stiffness": "iso6336", "exponent": 1.5, "damping_ratio": 0.05, "damping_Ns_mm": 50.0,
           "full_damping_penetration_mm": 0.1, **contact, **mesh}
    if any(key in {**contact, **mesh} for key in IMPACT) and "damping_ratio" not in {**contact, **mesh}:
        law["damping_ratio"] = None
    return law


def _step(x, x1, h1):
    """STEP(x, 0, 0, x1, h1) = h1 s^2 (3 - 2 s), s = x / x1 clamped to [0, 1] (DESIGN section 4)."""
    s = min(max(x / x1, 0.0), 1.0)
    return h1 * s * s * (3 - 2 * s)


def _i_total(doc: dict) -> float:
    return math.prod(st["gear"]["teeth"] / st["pinion"]["teeth"] for st in doc["stage"])


def _load_at(doc: dict, rpm_in: float) -> float:
    """The load torque (N m) at the output speed of input speed ``rpm_in``: [load] torque_Nm (n / n_0)^p, or a
    torque_speed table read linearly at the output speed."""
    load = doc["load"]
    if "torque_speed" in load:
        return _table_slope(load["torque_speed"], rpm_in / _i_total(doc))[1]
    return load["torque_Nm"] * (rpm_in / doc["input"]["speed_rpm"]) ** load.get("speed_exponent", 0)


def _efficiencies(doc: dict) -> list[float]:
    return [st.get("efficiency", 1.0) for st in doc["stage"]]


def _hand_meshes(doc: dict, load_scale: float = 1.0) -> list[dict]:
    """Every stage's hand mesh at the static load: the output torque reflected back through the stages. The law's
    force is the driving side's (DESIGN section 9): a forward load's pinion torque T_out / prod(i eta) drives; a
    reversed load (T_out < 0) drives from the gear, the pinion then gets T_out prod(eta / i) and the law carries
    that over its own stage's eta."""
    ratios, etas = [st["gear"]["teeth"] / st["pinion"]["teeth"] for st in doc["stage"]], _efficiencies(doc)
    t_out = _load_at(doc, doc["input"]["speed_rpm"]) * 1000.0  # the static load: at the nominal speed
    out = []
    for k, st in enumerate(doc["stage"]):
        if t_out >= 0:
            law_torque_Nmm = t_out / math.prod(i * eta for i, eta in zip(ratios[k:], etas[k:], strict=True))
        else:
            law_torque_Nmm = t_out * math.prod(eta / i for i, eta in zip(ratios[k:], etas[k:], strict=True)) / etas[k]
        out.append(_hand_mesh(st, _law(doc, k), law_torque_Nmm, load_scale))
    return out


def _table_slope(table, rpm):
    for (n0, t0), (n1, t1) in zip(table, table[1:], strict=False):
        if n0 <= rpm <= n1:
            return (t1 - t0) / ((n1 - n0) * RPM), t0 + (t1 - t0) * (rpm - n0) / (n1 - n0)
    raise AssertionError("speed outside the table")


def _operating_input_rpm(doc: dict) -> float:
    """The input speed: prescribed, or (a table motor) where the table meets the load reflected to the motor."""
    inp = doc["input"]
    if inp.get("drive") != "motor":
        return inp["speed_rpm"]
    i_tot = math.prod(st["gear"]["teeth"] / st["pinion"]["teeth"] for st in doc["stage"])
    p = doc["load"].get("speed_exponent", 0)
    n_out_nominal = inp["speed_rpm"] / i_tot

    def net(rpm):
        return _table_slope(inp["motor"]["torque_speed"], rpm)[1] \
            - doc["load"]["torque_Nm"] * (rpm / i_tot / n_out_nominal) ** p / i_tot

    return float(scipy.optimize.brentq(net, 1300.0, 1499.0, xtol=1e-12))


def _load_scale(doc: dict, rpm_in: float) -> float:
    """The load law's torque at the operating speed over its torque at the nominal speed."""
    return _load_at(doc, rpm_in) / _load_at(doc, doc["input"]["speed_rpm"])


def _hand_linear(doc: dict, at_operating_load: bool = False):
    """J, K, C over all bodies (motor?, shafts 1..n+1, drum?), the index of the speed-driven body or None.

    The meshes' and couplings' tangents at the design's static load (the load law at the nominal speed: what
    ``modes`` linearises, DESIGN section 13), or ``at_operating_load`` at the load the law gives at the operating
    speed (a motor drive's equilibrium: the right-hand side's own linearisation)."""
    rpm_in = _operating_input_rpm(doc)
    meshes = _hand_meshes(doc, _load_scale(doc, rpm_in) if at_operating_load else 1.0)
    inp, load = doc["input"], doc["load"]
    J = []
    if "coupling_stiffness_Nm_rad" in inp:
        J.append(inp["inertia_kg_m2"])
    first_shaft = len(J)
    stages = doc["stage"]
    # bodies: a rigid intermediate shaft carries gear k and pinion k+1; a flexible one ([stage.shaft]) is two
    # bodies, the gear end and the pinion end, joined by its spring (DESIGN section 6)
    pinion_body, gear_body, shafts = [len(J)], [], []
    J.append(stages[0]["pinion"]["inertia_kg_m2"])
    for k, st in enumerate(stages):
        gear_body.append(len(J))
        J.append(st["gear"]["inertia_kg_m2"])
        if k + 1 < len(stages):
            if "shaft" in st:
                shafts.append((len(J) - 1, len(J), st["shaft"]))
                J.append(0.0)
            pinion_body.append(len(J) - 1)
            J[-1] += stages[k + 1]["pinion"]["inertia_kg_m2"]
    if "coupling_stiffness_Nm_rad" in load:
        J.append(load["inertia_kg_m2"])
    n = len(J)
    driven = None if inp.get("drive") in ("torque", "motor") else 0
    Kmat, Cmat = np.zeros((n, n)), np.zeros((n, n))

    def add(a, b, ra, rb, k, c, eta=1.0):
        """A connector delta = ra theta_a - rb theta_b carrying f = k delta + c delta': the driving side takes f,
        the driven side eta f (DESIGN section 9; a forward load: a drives; reversed: b drives)."""
        lev, scatter = np.zeros(n), np.zeros(n)
        lev[a], lev[b] = ra, -rb
        forward = _load_at(doc, inp["speed_rpm"]) >= 0
        scatter[a], scatter[b] = (ra, -eta * rb) if forward else (eta * ra, -rb)
        Kmat[:] += k * np.outer(scatter, lev)
        Cmat[:] += c * np.outer(scatter, lev)

    if first_shaft:
        add(0, 1, 1.0, 1.0, inp["coupling_stiffness_Nm_rad"], inp.get("coupling_damping_Nms_rad", 0.0))
    for a, b, shaft in shafts:
        add(a, b, 1.0, 1.0, shaft["stiffness_Nm_rad"], shaft.get("damping_Nms_rad", 0.0))
    for k, (m, at_design) in enumerate(zip(meshes, _hand_meshes(doc), strict=True)):
        p, g = pinion_body[k], gear_body[k]
        inv = (0.0 if p == driven else m["rb1"] ** 2 / J[p]) + m["rb2"] ** 2 / J[g]
        law = _law(doc, k)
        if law["damping_ratio"] is None:  # IMPACT: F_n = K h^e + STEP(h, 0, 0, d, C) h', h = cos(beta_b) delta
            c = m["cos_bb"] ** 2 * _step(m["h_op_mm"], law["full_damping_penetration_mm"],
                                         law["damping_Ns_mm"] * 1000.0)
        else:  # c = 2 zeta sqrt(k_lin m_e), k_lin at the design's static load (N/m along the normal): a constant
            c = 2 * law["damping_ratio"] * math.sqrt(at_design["k_lin"] * 1000.0 / inv)
        add(p, g, m["rb1"], m["rb2"], m["k_lin"] * 1000.0 * m["cos_bb"] ** 2, c, _efficiencies(doc)[k])
    if "coupling_stiffness_Nm_rad" in load:
        add(n - 2, n - 1, 1.0, 1.0, load["coupling_stiffness_Nm_rad"], load.get("coupling_damping_Nms_rad", 0.0))
    if inp.get("drive") == "motor":
        Cmat[0, 0] -= _table_slope(inp["motor"]["torque_speed"], rpm_in)[0]
    p = load.get("speed_exponent", 0)
    if p:
        i_tot = math.prod(m["ratio"] for m in meshes)
        w, w_n = rpm_in * RPM / i_tot, inp["speed_rpm"] * RPM / i_tot
        Cmat[n - 1, n - 1] += p * load["torque_Nm"] * w ** (p - 1) / w_n**p
    if "torque_speed" in load:  # the slope of the table's segment at the output speed, N m s/rad
        Cmat[n - 1, n - 1] += _table_slope(load["torque_speed"], rpm_in / _i_total(doc))[0]
    return np.array(J), Kmat, Cmat, driven, meshes, rpm_in


def _damped(J, K, C):
    n = len(J)
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-K / J[:, None], -C / J[:, None]]])
    return np.linalg.eigvals(A)


def _design(doc):
    cfg = DesignFile.model_validate(copy.deepcopy(doc))
    return cfg, compute_design(cfg)


def _operating_state(doc, model):
    """The static operating point in the model's state layout, built from the hand calculation: each mesh's
    deflection delta0 = h0 / cos beta_b with F_n0 = K h0^e at the actual static force, each coupling's twist T / k,
    every body at its rigid speed."""
    _, _, _, _, meshes, rpm_in = _hand_linear(doc)
    lay = model.layout
    st = lay.state
    y = model.initial_state()
    w_in = rpm_in * RPM
    for i in lay.free_bodies:
        y[st.omega(i)] = lay.bodies[i].ratio * w_in
    load = doc["load"]
    t_out = _load_at(doc, rpm_in)
    etas = _efficiencies(doc)
    t_in = t_out / math.prod(m["ratio"] * eta for m, eta in zip(meshes, etas, strict=True)) if t_out >= 0 else \
        t_out * math.prod(eta / m["ratio"] for m, eta in zip(meshes, etas, strict=True))
    hand = iter(meshes)
    for c, x in enumerate(lay.connectors):
        if x.role == "mesh":  # the drive flank, or the back flank (delta < 0) of a reversed load
            m = next(hand)
            h0 = (m["f_n"] * (t_out / _load_at(doc, doc["input"]["speed_rpm"])) / m["K"]) ** (1 / m["e"]) / 1000.0
            y[st.delta(c)] = math.copysign(h0 / m["cos_bb"], t_out)
        elif x.label.startswith("input"):
            y[st.delta(c)] = t_in / doc["input"]["coupling_stiffness_Nm_rad"]
        else:
            y[st.delta(c)] = t_out / load["coupling_stiffness_Nm_rad"]
    return y


def _cli_json(tmp_path, doc, command, *extra):
    path = tmp_path / "scene.toml"
    path.write_text(tomli_w.dumps(doc), encoding="utf-8")
    res = CliRunner().invoke(cli, [command, str(path), "--format", "json", "-q", *extra])
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout)


def _json_laws(command, d):
    if command == "design":
        return [s["mesh_stiffness"] for s in d["stages"]]
    if command == "modes":
        return [m["mesh_stiffness"] for m in d["meshes"]]
    return [s["mesh_stiffness"] for s in d["summary"]["stages"]]


def _with_duty(doc):
    """THREE_SPEED with a rating-free duty cycle: 600 N m at 1470 rpm, 30 kW at 980 rpm (T = P / w_out by hand),
    a light 40 N m at 1470 rpm with the exponent raised to 2.0 for that point only (``set``)."""
    out = copy.deepcopy(doc)
    # what gearcli life needs to rate the members (it plays no part in the stiffness)
    out["materials"]["steel"].update({"treatment": "case_carburized", "contact_fatigue_limit_MPa": 1500.0,
                                      "bending_fatigue_limit_MPa": 500.0})
    for st in out["stage"]:
        st["accuracy_grade"] = 6
        for member in ("pinion", "gear"):
            st[member].update({"flank_roughness_Rz_um": 4.0, "root_roughness_Rz_um": 12.0})
    out["lubricant"] = {"viscosity_40C_mm2_s": 220.0}
    out["rating"] = {"required_life_h": 20000.0}
    out["duty"] = [{"name": "a", "hours": 100.0, "torque_Nm": 600.0, "speed_rpm": 1470.0},
                   {"name": "b", "hours": 100.0, "power_kW": 30.0, "speed_rpm": 980.0},
                   {"name": "c", "hours": 100.0, "torque_Nm": 40.0, "speed_rpm": 1470.0,
                    "set": {"contact.exponent": 2.0}}]
    return out


# a sun-driven spur planetary 20/31/82 (3 planets, ring held, m_n 3, b 40) with Hertz meshes at e = 1.3 and a
# helical stage after it on the calibrated law at the same exponent
PLANETARY = {
    "materials": {"steel": STEEL},
    "contact": {"exponent": 1.3},
    "stage": [{"type": "planetary", "normal_module_mm": 3.0, "normal_pressure_angle_deg": 20.0,
               "sun": {"teeth": 20, "face_width_mm": 40.0, "material": "steel", "inertia_kg_m2": 0.002},
               "planet": {"teeth": 31, "face_width_mm": 40.0, "count": 3, "material": "steel",
                          "inertia_kg_m2": 0.004, "mass_kg": 1.5},
               "ring": {"teeth": 82, "face_width_mm": 40.0, "material": "steel"},
               "carrier": {"inertia_kg_m2": 0.3}, "fixed": "ring", "input": "sun", "mesh": {"stiffness": "hertz"}},
              _stage(5.0, 12.0, 19, 77, 70.0, 65.0, 0.02, 1.4)],
    "input": {"speed_rpm": 1500.0, "ramp_s": 0.02},
    "load": {"torque_Nm": 9000.0, "ramp_s": 0.02},
    "simulation": {"duration_s": 0.06, "steps": 120},
}


def _hand_planetary() -> dict:
    """The two planet meshes by hand (spur, x = 0, m_t = m_n = 3 mm, alpha_t = 20 deg).
    Per planet F_t = T_sun / (3 r_s), T_sun = T_carrier / (1 + z_r / z_s), T_carrier = 9000 N m x 19/77.
    Sun-planet: external, the formulas above. Planet-ring: R = r_p r_r / (r_r - r_p) (concave Hertz contact),
    ISO 6336-1 q' with z_n2 = infinity for the internal gear, eps_alpha = (sqrt(r_ap^2 - r_bp^2) - sqrt(r_ar^2 -
    r_br^2) + a sin alpha_t) / (pi m_t cos alpha_t), r_ar = r_r - m_n (internal tips), a = r_r - r_p."""
    a_t, m = math.radians(20.0), 3.0
    r_s, r_p, r_r = 30.0, 46.5, 123.0
    f_t = 9000e3 * 19 / 77 / (1 + 82 / 20) / (3 * r_s)
    f_n = f_t / math.cos(a_t)
    e_star = 1 / (2 * (1 - 0.3**2) / 2.1e5)
    c_b = 1 + 0.5 * (1.2 - 1.25)
    out = {}
    for name, radius, q, eps in (
        ("sun_planet", r_s * r_p / (r_s + r_p), Q_COEF[0] + Q_COEF[1] / 20 + Q_COEF[2] / 31,
         (math.sqrt((r_s + m) ** 2 - (r_s * math.cos(a_t)) ** 2) + math.sqrt((r_p + m) ** 2 - (r_p * math.cos(a_t)) ** 2)
          - (r_s + r_p) * math.sin(a_t)) / (math.pi * m * math.cos(a_t))),
        ("planet_ring", r_p * r_r / (r_r - r_p), Q_COEF[0] + Q_COEF[1] / 31,
         (math.sqrt((r_p + m) ** 2 - (r_p * math.cos(a_t)) ** 2) - math.sqrt((r_r - m) ** 2 - (r_r * math.cos(a_t)) ** 2)
          + (r_r - r_p) * math.sin(a_t)) / (math.pi * m * math.cos(a_t)))):
        k_n = 1 / q * 0.8 * c_b * (0.75 * eps + 0.25) * 40.0 * 1000.0  # F_t / b = 121 N/mm: full load
        K = 4 / 3 * math.sqrt(radius) * e_star
        h0 = (f_n / K) ** (1 / 1.3)
        out[name] = {"K": K, "k_lin": 1.3 * K * h0**0.3, "k_n": k_n}
    return out
