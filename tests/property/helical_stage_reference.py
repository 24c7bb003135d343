"""An independent reference for `gearcli design` on parallel helical stages (test helper, no gearcli imports).

Written from ISO 21771 (geometry, tooth thickness, backlash), ISO 6336-1 method B (c′, c_γα, C_B, C_R, m_red, n_E1,
N_S) and the product contract (DESIGN sections 2, 3, 7, 9, 13), not from gearcli's code. Where the contract and a
textbook differ the contract's choice is taken and named here:
- the static forces act on the reference (not the working) pitch circle: F_t = T_1 / r_1, F_r = F_t tan α_t;
- the Hertz radius takes the reference pitch radii;
- b is the smaller face width (ε_β, F_t/b, c_γα b);
- c_γα = c′ (0.75 ε_α + 0.25) with no 0.9 factor below ε_α = 1.2 (DESIGN section 7 and docs/iso6336.md, which
  give their reason; section 3 of the contract still asks for the factor);
- the calibrated law's tangent e K h0^(e−1) equals k_n = c_γα b / cos² β_b at the static normal force (section 13);
- gearcli's documented floors (docs/iso6336.md, docs/physics.md): ISO's F_t/b is taken at no less than 1 N/mm (then
  times K_A), and the law is calibrated at no less than that load, so below it the tangent at the static load is
  softer than k_n;
- the model's inertia is the solid pitch disc (section 2) unless a bore, rim or web describes the body; then, as for
  m_red always, ρ π b (d_m⁴ − d_bore⁴)/32 with d_m = (d_a + d_f)/2 (section 7); C_R of a webbed member from ISO
  6336-1 and the mean of the two members' C_R when they differ (docs/iso6336.md).
Units: mm, N, N·mm, MPa, rpm; stiffness per face width in N/(mm·µm).

The backlash is derived here on the working circle from first principles (tooth thickness on a circle of the involute,
ISO 21771 eq. for s_y) rather than from the docs' closed form: the two must agree, which is a check of its own.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from math import acos, atan, cos, exp, log, pi, radians, sin, sqrt, tan

Q_COEFFS = (0.04723, 0.15551, 0.25791, -0.00635, -0.11654, -0.00193, -0.24188, 0.00529, 0.00182)


def inv(alpha: float) -> float:
    return tan(alpha) - alpha


def inv_inverse(value: float) -> float:
    """α with inv α = value (value >= 0), by bisection then Newton (independent of any starting guess's quality)."""
    lo, hi = 0.0, 1.5
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if inv(mid) < value else (lo, mid)
    a = 0.5 * (lo + hi)
    for _ in range(5):
        a -= (inv(a) - value) / tan(a) ** 2 if a > 0 else 0.0
    return a


@dataclass
class Member:
    teeth: int
    face_width: float
    shift: float = 0.0
    youngs: float = 2.07e5
    poisson: float = 0.29
    density: float = 7800.0
    thickness_allowance: tuple[float, float] | None = None  # (A_sne, A_sni), mm
    tip_allowance: tuple[float, float] = (0.0, 0.0)           # (A_dae, A_dai), mm
    bore: float | None = None                                  # bore diameter, mm
    web: tuple[float, float] | None = None                     # (rim thickness s_R, web thickness b_s), mm


@dataclass
class Stage:
    m_n: float
    alpha_n_deg: float
    beta_deg: float
    pinion: Member
    gear: Member
    efficiency: float = 1.0
    rack: tuple[float, float, float] = (1.0, 1.25, 0.38)  # h_aP*, h_fP*, ρ_fP*
    center_allowance: tuple[float, float] = (0.0, 0.0)   # (A_ae, A_ai), mm
    out: dict = field(default_factory=dict)


def geometry(s: Stage) -> dict:
    """ISO 21771 geometry of one external pair with profile shift and tip alteration."""
    m_n, a_n, beta = s.m_n, radians(s.alpha_n_deg), radians(s.beta_deg)
    h_a, h_f, _rho = s.rack
    z1, z2 = s.pinion.teeth, s.gear.teeth
    x1, x2 = s.pinion.shift, s.gear.shift
    m_t = m_n / cos(beta)
    a_t = atan(tan(a_n) / cos(beta))
    b_b = atan(tan(beta) * cos(a_t))
    d = (z1 * m_t, z2 * m_t)
    d_b = (d[0] * cos(a_t), d[1] * cos(a_t))
    a_d = 0.5 * (d[0] + d[1])
    a_wt = inv_inverse(inv(a_t) + 2.0 * tan(a_n) * (x1 + x2) / (z1 + z2))
    a_w = a_d * cos(a_t) / cos(a_wt)
    k = (a_w - a_d) / m_n - (x1 + x2)
    d_a = (d[0] + 2 * m_n * (h_a + x1 + k), d[1] + 2 * m_n * (h_a + x2 + k))
    d_f = (d[0] - 2 * m_n * (h_f - x1), d[1] - 2 * m_n * (h_f - x2))
    p_bt = pi * m_t * cos(a_t)
    eps_a = transverse_contact_ratio(d_a, d_b, a_w, p_bt)
    b = min(s.pinion.face_width, s.gear.face_width)
    eps_b = b * sin(beta) / (pi * m_n)
    return {"m_t": m_t, "a_t": a_t, "a_wt": a_wt, "b_b": b_b, "d": d, "d_b": d_b, "d_a": d_a, "d_f": d_f,
            "a_d": a_d, "a_w": a_w, "k": k, "p_bt": p_bt, "eps_a": eps_a, "eps_b": eps_b, "b": b}


def transverse_contact_ratio(d_a, d_b, centre: float, p_bt: float) -> float:
    """Path of contact between the tip circles along the line of action at `centre`, over the base pitch."""
    a_w = acos(0.5 * (d_b[0] + d_b[1]) / centre)  # the working pressure angle at that centre distance
    path = sum(sqrt((0.5 * da) ** 2 - (0.5 * db) ** 2) for da, db in zip(d_a, d_b, strict=True)) - centre * sin(a_w)
    return path / p_bt


def tooth_thickness_normal_at(diameter: float, d: float, d_b: float, x: float, m_n: float, a_n: float,
                              beta: float, a_t: float) -> float:
    """Normal-section tooth thickness on a circle of `diameter` (ISO 21771: s_yt = d_y (s_t/d + inv α_t − inv α_yt),
    s_yn = s_yt cos β_y, tan β_y = tan β d_y / d)."""
    s_t = m_n * (pi / 2 + 2 * x * tan(a_n)) / cos(beta)
    a_y = acos(d_b / diameter)
    s_yt = diameter * (s_t / d + inv(a_t) - inv(a_y))
    return s_yt * cos(atan(tan(beta) * diameter / d))


def undercut_min_shift(s: Stage, z: int) -> float:
    """x_min = h_aP0* − ρ_aP0* (1 − sin α_n) − z sin² α_t / (2 cos β): the tool (h_aP0 = h_fP) generates no undercut."""
    a_n, beta = radians(s.alpha_n_deg), radians(s.beta_deg)
    a_t = atan(tan(a_n) / cos(beta))
    return s.rack[1] - s.rack[2] * (1 - sin(a_n)) - z * sin(a_t) ** 2 / (2 * cos(beta))


def iso6336(s: Stage, g: dict, f_t: float, k_a: float) -> dict:
    """ISO 6336-1 method B: c′ and c_γα (index 1 the smaller wheel; equal counts: the smaller shift, docs/iso6336.md),
    C_B of the basic rack, the load correction."""
    beta = radians(s.beta_deg)
    members = sorted([s.pinion, s.gear], key=lambda m: (m.teeth, m.shift))
    z_n = [m.teeth / (cos(g["b_b"]) ** 2 * cos(beta)) for m in members]
    x = [m.shift for m in members]
    c = Q_COEFFS
    q = (c[0] + c[1] / z_n[0] + c[2] / z_n[1] + c[3] * x[0] + c[4] * x[0] / z_n[0] + c[5] * x[1]
         + c[6] * x[1] / z_n[1] + c[7] * x[0] ** 2 + c[8] * x[1] ** 2)
    c_m = 0.8
    c_r_each = [blank_factor(m, s.m_n) for m in (s.pinion, s.gear)]
    c_r = c_r_each[0] if c_r_each[0] == c_r_each[1] else 0.5 * (c_r_each[0] + c_r_each[1])  # docs/iso6336.md
    c_b = (1 + 0.5 * (1.2 - s.rack[1])) * (1 - 0.02 * (20.0 - s.alpha_n_deg))
    c_p = c_m * c_r * c_b * cos(beta) / q
    load = max(abs(f_t) / g["b"], 1.0) * k_a  # gearcli floors F_t/b at 1 N/mm (docs/iso6336.md), then K_A
    if load < 100.0:
        c_p *= (load / 100.0) ** 0.25
    c_ga = c_p * (0.75 * g["eps_a"] + 0.25)
    return {"c_p": c_p, "c_ga": c_ga, "c_gb": 0.85 * c_ga, "C_B": c_b, "C_M": c_m, "C_R": c_r, "C_R_each": c_r_each,
            "load_per_b": load}


def allowances(s: Stage, g: dict) -> dict:
    """ISO 21771 tooth-thickness allowances: x_E, cut roots, backlash (max, min) and ε_α at the allowance limits."""
    m_n, a_n, beta = s.m_n, radians(s.alpha_n_deg), radians(s.beta_deg)
    mem = (s.pinion, s.gear)
    a_sn = [m.thickness_allowance or (0.0, 0.0) for m in mem]
    x_e = [(m.shift + a[0] / (2 * m_n * tan(a_n)), m.shift + a[1] / (2 * m_n * tan(a_n))) for m, a in zip(mem, a_sn, strict=True)]
    d_f_cut = [tuple(g["d"][j] - 2 * m_n * (s.rack[1] - xe) for xe in x_e[j]) for j in (0, 1)]

    def backlash_t(centre: float, xs: tuple[float, float]) -> float:
        """Circumferential backlash on the working circle at `centre`: its pitch less both cut thicknesses there."""
        a_w = acos(g["a_d"] * cos(g["a_t"]) / centre)
        s_w = []
        for j in (0, 1):
            d_w = g["d_b"][j] / cos(a_w)
            s_t = m_n * (pi / 2 + 2 * xs[j] * tan(a_n)) / cos(beta)
            s_w.append(d_w * (s_t / g["d"][j] + inv(g["a_t"]) - inv(a_w)))
        d_w1 = g["d_b"][0] / cos(a_w)
        return pi * d_w1 / s.pinion.teeth - s_w[0] - s_w[1]

    a_e, a_i = s.center_allowance
    j_max = backlash_t(g["a_w"] + a_e, (x_e[0][1], x_e[1][1]))
    j_min = backlash_t(g["a_w"] + a_i, (x_e[0][0], x_e[1][0]))

    def to_normal(j_t: float, centre: float) -> float:
        return j_t * (0.5 * (g["d_b"][0] + g["d_b"][1]) / centre) * cos(g["b_b"])

    tips = [tuple(g["d_a"][j] + mem[j].tip_allowance[k] for k in (0, 1)) for j in (0, 1)]
    eps_e = transverse_contact_ratio((tips[0][0], tips[1][0]), g["d_b"], g["a_w"] + a_i, g["p_bt"])
    eps_i = transverse_contact_ratio((tips[0][1], tips[1][1]), g["d_b"], g["a_w"] + a_e, g["p_bt"])
    eps_m = transverse_contact_ratio((sum(tips[0]) / 2, sum(tips[1]) / 2), g["d_b"], g["a_w"] + (a_e + a_i) / 2,
                                     g["p_bt"])
    return {"x_E": x_e, "d_f_cut": d_f_cut, "j_t": (j_max, j_min),
            "j_n": (to_normal(j_max, g["a_w"] + a_e), to_normal(j_min, g["a_w"] + a_i)),
            "eps_allow": (eps_e, eps_m, eps_i)}


def interference(s: Stage, g: dict, shifts: tuple[float, float] | None = None) -> dict:
    """Involute interference along the line of action (distances from the pinion's base tangent point T1).

    A member's involute is generated down to its form point, where the rack's straight flank (height
    h_FfP* = h_fP* − ρ_fP* (1 − sin α_n) above the datum, less x) ends: q = r sin α_t − (h_FfP* − x) m_n / sin α_t from
    its own base tangent point (q < 0: undercut, the involute starts at the base circle at best). The mate's tip
    circle starts (ends) contact at A = a_w sin α_wt − ρ_a2 (E = ρ_a1). Contact below a form point is interference:
    depth = form point − A; the usable ε_α counts the path between the form points only."""
    a_n = radians(s.alpha_n_deg)
    h_ff = s.rack[1] - s.rack[2] * (1 - sin(a_n))
    xs = shifts or (s.pinion.shift, s.gear.shift)
    q = [g["d"][j] / 2 * sin(g["a_t"]) - (h_ff - xs[j]) * s.m_n / sin(g["a_t"]) for j in (0, 1)]
    rho_a = [sqrt((g["d_a"][j] / 2) ** 2 - (g["d_b"][j] / 2) ** 2) for j in (0, 1)]
    line = g["a_w"] * sin(g["a_wt"])
    start, end = line - rho_a[1], rho_a[0]
    low, high = max(q[0], 0.0), line - max(q[1], 0.0)
    return {"q": q, "pinion": low - start, "gear": end - high,
            "usable": (min(end, high) - max(start, low)) / g["p_bt"],
            "form_diameter": tuple(2 * sqrt((g["d_b"][j] / 2) ** 2 + q[j] ** 2) if q[j] >= 0 else None for j in (0, 1))}


def disc_inertia(density: float, face_width: float, diameter: float) -> float:
    """Solid disc, kg·m²: ρ π b d⁴ / 32 (mm in, m out)."""
    return density * pi * (face_width * 1e-3) * (diameter * 1e-3) ** 4 / 32.0


def train(stages: list[Stage], speed_in_rpm: float, torque_out_Nm: float, k_a: float = 1.0,
          exponent: float = 1.5) -> list[Stage]:
    """Speeds down the train, torques up from the load (η against the power flow), then every stage's figures
    in `Stage.out`."""
    speeds = []
    n = speed_in_rpm
    for s in stages:
        i = s.gear.teeth / s.pinion.teeth
        speeds.append((n, n / i))
        n /= i
    torques = [(0.0, 0.0)] * len(stages)
    t = torque_out_Nm
    for k in range(len(stages) - 1, -1, -1):
        s = stages[k]
        i = s.gear.teeth / s.pinion.teeth
        t_p = t / (i * s.efficiency) if t >= 0 else t * s.efficiency / i  # power to the load, or back from it
        torques[k] = (t_p, t)
        t = t_p
    for s, (n_p, n_g), (t_p, t_g) in zip(stages, speeds, torques, strict=True):
        s.out = stage_figures(s, n_p, n_g, t_p * 1e3, t_g * 1e3, k_a, exponent)
    return stages


def stage_figures(s: Stage, n_p: float, n_g: float, t_p: float, t_g: float, k_a: float, exponent: float) -> dict:
    g = geometry(s)
    beta, a_n = radians(s.beta_deg), radians(s.alpha_n_deg)
    r1, r2 = g["d"][0] / 2, g["d"][1] / 2
    f_t = t_p / r1
    forces = {"tangential": f_t, "radial": f_t * tan(g["a_t"]), "axial": f_t * tan(beta),
              "normal": f_t / (cos(a_n) * cos(beta))}
    e_star = 1.0 / ((1 - s.pinion.poisson ** 2) / s.pinion.youngs + (1 - s.gear.poisson ** 2) / s.gear.youngs)
    r_eq = r1 * r2 / (r1 + r2)
    k_hertz = 4.0 / 3.0 * sqrt(r_eq) * e_star
    iso = iso6336(s, g, f_t, k_a)
    k_n = iso["c_ga"] * 1e3 * g["b"] / cos(g["b_b"]) ** 2  # N/mm along the normal
    # The mesh law carries the driving member's force: F_n, or F_n / η when the load drives back through a lossy
    # mesh (DESIGN section 9). Its tangent equals k_n there (section 13), the load floored at 1 N/mm of face as
    # ISO's evaluation is (docs/iso6336.md), so an idle mesh keeps a finite K.
    f_n = abs(forces["normal"]) / (s.efficiency if t_p < 0 else 1.0)
    f_cal = max(f_n, g["b"] / (cos(a_n) * cos(beta)))
    h_cal = exponent * f_cal / k_n
    law_k = f_cal / h_cal ** exponent
    h0 = (f_n / law_k) ** (1 / exponent)
    j_pitch = (disc_inertia(s.pinion.density, s.pinion.face_width, g["d"][0]),
               disc_inertia(s.gear.density, s.gear.face_width, g["d"][1]))
    j_body = tuple(disc_inertia(m.density, m.face_width, 0.5 * (g["d_a"][j] + g["d_f"][j]))
                   - (disc_inertia(m.density, m.face_width, m.bore) if m.bore else 0.0)
                   for j, m in enumerate((s.pinion, s.gear)))
    # the model's inertia: the pitch disc of DESIGN section 2 unless the body is described (docs/iso6336.md)
    j_model = tuple(j_body[j] if (m.bore or m.web) else j_pitch[j] for j, m in enumerate((s.pinion, s.gear)))
    # ISO 6336-1 m_red (kg/mm): each wheel's inertia per unit face width over r_b²
    m_star = [j_body[j] * 1e6 / (m.face_width * (g["d_b"][j] / 2) ** 2) for j, m in enumerate((s.pinion, s.gear))]
    m_red = m_star[0] * m_star[1] / (m_star[0] + m_star[1])
    small = 0 if s.pinion.teeth <= s.gear.teeth else 1
    z_small = (s.pinion.teeth, s.gear.teeth)[small]
    n_e1 = 3e4 / (pi * z_small) * sqrt(iso["c_ga"] / m_red)
    load = iso["load_per_b"]
    n_s = 0.85 if load >= 100 else 0.5 + 0.35 * sqrt(load / 100)  # F_t K_A / b with the same floor
    x_e_i = tuple(m.shift + (m.thickness_allowance or (0.0, 0.0))[1] / (2 * s.m_n * tan(a_n))
                  for m in (s.pinion, s.gear))
    members = (s.pinion, s.gear)

    def tip_thickness(j: int, tip_allowance: float, x: float) -> float:
        return tooth_thickness_normal_at(g["d_a"][j] + tip_allowance, g["d"][j], g["d_b"][j], x, s.m_n, a_n, beta,
                                         g["a_t"])
    return {"geometry": g, "ratio": s.gear.teeth / s.pinion.teeth, "speeds": (n_p, n_g), "torques": (t_p, t_g),
            "forces": forces, "e_star": e_star, "r_eq": r_eq, "K_hertz": k_hertz, "iso": iso, "k_n": k_n,
            "h0": h0, "law_K": law_k, "h_cal": h_cal, "k_lin": exponent * law_k * h0 ** (exponent - 1),
            "f_z": s.pinion.teeth * n_p / 60.0, "J_model": j_model, "J_body": j_body,
            "m_red": m_red, "n_E1": n_e1, "N": (n_p, n_g)[small] / n_e1, "N_S": n_s,
            "allow": allowances(s, g), "interference": interference(s, g),
            "undercut_x_min": tuple(undercut_min_shift(s, m.teeth) for m in members), "x_E_i": x_e_i,
            # the cut tooth: the thinnest (x_E,i) on the largest tip (d_a + A_dae); and the nominal one
            "tip_thickness_cut": tuple(tip_thickness(j, m.tip_allowance[0], x_e_i[j]) for j, m in enumerate(members)),
            "tip_thickness": tuple(tip_thickness(j, 0.0, m.shift) for j, m in enumerate(members))}


def blank_factor(m: Member, m_n: float) -> float:
    """ISO 6336-1 C_R = 1 + ln(b_s/b) / (5 e^(s_R/(5 m_n))) of a webbed member (b_s/b within 0.2 … 1.2, s_R ≥ m_n);
    1 for a solid one."""
    if m.web is None:
        return 1.0
    rim, web = m.web
    return 1 + log(min(max(web / m.face_width, 0.2), 1.2)) / (5 * exp(max(rim, m_n) / (5 * m_n)))
