"""An independent hand calculation of one external helical pair for the heavy-reducer tests.

Every formula is typed again here from ISO 21771:2007 (geometry), ISO 6336-1:2006 method B (c′, c_γα, m_red, n_E1,
K_v, K_Fβ), ISO 6336-2:2006 (with Cor. 1:2008 for Z_β), ISO 6336-3:2006 method B (Y_F, Y_S), ISO 6336-5 (life
factors) and ISO 1328-1:1995 (f_pt, f_fα of a flank tolerance class), in the notation docs/iso6336.md quotes; it
imports nothing from gearcli. Lengths in mm, forces in N, torques in N·mm, stresses in MPa, speeds in rpm.
"""

from __future__ import annotations

import math

Q_COEFF = (0.04723, 0.15551, 0.25791, -0.00635, -0.11654, -0.00193, -0.24188, 0.00529, 0.00182)


def inv(a: float) -> float:
    return math.tan(a) - a


def inv_inverse(v: float) -> float:
    """α with inv α = v by bisection (independent of any Newton solve)."""
    lo, hi = 1e-9, 1.5
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if inv(mid) < v else (lo, mid)
    return 0.5 * (lo + hi)


def pair(mn, an_deg, beta_deg, z, x, b, t1_nmm, n1_rpm, e=(206000.0, 206000.0), nu=(0.3, 0.3),
         rho=(7830e-9, 7830e-9), ha=1.0, hf=1.25, rho_f=0.38) -> dict:
    """ISO 21771 geometry, statics and Hertz figures of a pinion (index 0) driving a gear (index 1)."""
    an, be = math.radians(an_deg), math.radians(beta_deg)
    mt = mn / math.cos(be)                                    # transverse module
    at = math.atan(math.tan(an) / math.cos(be))               # transverse pressure angle
    bb = math.atan(math.tan(be) * math.cos(at))               # base helix angle
    d = [zi * mt for zi in z]
    db = [di * math.cos(at) for di in d]
    awt = inv_inverse(inv(at) + 2 * math.tan(an) * (x[0] + x[1]) / (z[0] + z[1]))  # working pressure angle
    a = (d[0] + d[1]) / 2
    aw = a * math.cos(at) / math.cos(awt)                     # working centre distance
    k = (aw - a) / mn - (x[0] + x[1])                         # tip alteration (≤ 0)
    da = [d[i] + 2 * mn * (ha + x[i] + k) for i in (0, 1)]
    df = [d[i] - 2 * mn * (hf - x[i]) for i in (0, 1)]
    pbt = math.pi * mt * math.cos(at)
    ea = (math.sqrt((da[0] / 2) ** 2 - (db[0] / 2) ** 2) + math.sqrt((da[1] / 2) ** 2 - (db[1] / 2) ** 2)
          - aw * math.sin(awt)) / pbt
    bmin = min(b)
    eb = bmin * math.sin(be) / (math.pi * mn)
    ft = t1_nmm / (d[0] / 2)
    r_eq = 1 / (2 / d[0] + 2 / d[1])
    e_star = 1 / ((1 - nu[0] ** 2) / e[0] + (1 - nu[1] ** 2) / e[1])
    j_pitch = [rho[i] * math.pi * b[i] * d[i] ** 4 / 32 * 1e-6 for i in (0, 1)]  # kg m² (ρ in kg/mm³, mm⁵ → ×1e-6)
    return dict(mn=mn, an=an, be=be, mt=mt, at=at, bb=bb, z=tuple(z), x=tuple(x), b=tuple(b), bmin=bmin, d=d, db=db,
                da=da, df=df, awt=awt, aw=aw, k=k, pbt=pbt, ea=ea, eb=eb, eg=ea + eb, u=z[1] / z[0], n1=n1_rpm,
                t1=t1_nmm, ft=ft, fr=ft * math.tan(at), fa=ft * math.tan(be), fn=ft / (math.cos(an) * math.cos(be)),
                r_eq=r_eq, e_star=e_star, hertz_k=4 / 3 * math.sqrt(r_eq) * e_star, fz=z[0] * n1_rpm / 60,
                rho=rho, ha=ha, hf=hf, rho_f=rho_f, j_pitch=j_pitch)


def virtual_teeth(g: dict, i: int) -> float:
    return g["z"][i] / (math.cos(g["bb"]) ** 2 * math.cos(g["be"]))


def stiffness(g: dict, k_a: float) -> dict:
    """ISO 6336-1 clause 9 (solid blanks, C_R = 1) and 6.5: c′, c_γα, m_red, n_E1, N, N_S (index 1 = fewer teeth)."""
    s, l = (0, 1) if g["z"][0] <= g["z"][1] else (1, 0)
    zn1, zn2, x1, x2 = virtual_teeth(g, s), virtual_teeth(g, l), g["x"][s], g["x"][l]
    c = Q_COEFF
    q = (c[0] + c[1] / zn1 + c[2] / zn2 + c[3] * x1 + c[4] * x1 / zn1 + c[5] * x2 + c[6] * x2 / zn2
         + c[7] * x1 ** 2 + c[8] * x2 ** 2)
    c_b = (1 + 0.5 * (1.2 - g["hf"])) * (1 - 0.02 * (20 - math.degrees(g["an"])))
    line = g["ft"] * k_a / g["bmin"]
    c_p = 1 / q * 0.8 * 1.0 * c_b * math.cos(g["be"]) * (min(line, 100.0) / 100) ** 0.25
    c_ga = c_p * (0.75 * g["ea"] + 0.25)
    d_m = [(g["da"][i] + g["df"][i]) / 2 for i in (0, 1)]
    # m* = J/b / r_b², J = π ρ b d_m⁴/32 (ISO's body: the mean of tip and root diameters), kg/mm
    m_star = [math.pi * g["rho"][i] * 1e9 * (d_m[i] * 1e-3) ** 4 / 32 / (g["db"][i] / 2e3) ** 2 * 1e-3
              for i in (0, 1)]
    m_red = m_star[0] * m_star[1] / (m_star[0] + m_star[1])
    n_e1 = 30000 / (math.pi * g["z"][s]) * math.sqrt(c_ga / m_red)
    n_small = g["n1"] * g["z"][0] / g["z"][s]
    n_s = 0.85 if line >= 100 else 0.5 + 0.35 * math.sqrt(line / 100)
    return dict(c_p=c_p, c_ga=c_ga, c_gb=0.85 * c_ga, c_b=c_b, m_red=m_red, n_e1=n_e1, N=n_small / n_e1, N_S=n_s)


# ISO 1328-1:1995 class 5 at the geometric mean of the standard's ranges, × 2^((Q − 5)/2), rounded
D_RANGES = (5, 20, 50, 125, 280, 560, 1000, 1600, 2500, 4000, 6000, 8000, 10000)
M_RANGES = (0.5, 2, 3.5, 6, 10, 16, 25, 40, 70)


def _mean_of_range(v: float, edges: tuple) -> float:
    v = min(max(v, edges[0]), edges[-1])
    return next(math.sqrt(lo * hi) for lo, hi in zip(edges, edges[1:], strict=False) if v <= hi)


def _round_1328(v: float) -> float:
    return float(round(v)) if v > 10 else (round(2 * v) / 2 if v >= 5 else round(v, 1))


def tolerances(d: float, m: float, grade: int) -> tuple[float, float]:
    """(f_pt, f_fα) in µm of one member."""
    dm, mm = _mean_of_range(d, D_RANGES), _mean_of_range(m, M_RANGES)
    scale = 2 ** ((grade - 5) / 2)
    return (_round_1328((0.3 * (mm + 0.4 * math.sqrt(dm)) + 4) * scale),
            _round_1328((2.5 * math.sqrt(mm) + 0.17 * math.sqrt(dm) + 0.5) * scale))


def k_v_subcritical(g: dict, st: dict, grade: int, k_a: float, running_in) -> float:
    """ISO 6336-1 method B, subcritical range, C_a = 0 (B_k = 1); ``running_in(f)`` the pair's y for a deviation f."""
    f_pt = max(tolerances(g["d"][i], g["mn"], grade)[0] for i in (0, 1))
    f_fa = max(tolerances(g["d"][i], g["mn"], grade)[1] for i in (0, 1))
    f_pb = f_pt * math.cos(g["at"])
    line = k_a * g["ft"] / g["bmin"]
    b_p = st["c_p"] * (f_pb - running_in(f_pb)) / line
    b_f = st["c_p"] * (f_fa - running_in(f_fa)) / line
    eg = g["eg"]
    c1, c2, c3 = (0.32, 0.34, 0.23) if eg <= 2 else (0.32, 0.57 / (eg - 0.3), 0.096 / (eg - 1.56))
    assert st["N"] <= st["N_S"], "the hand K_v covers the subcritical range only"
    return 1 + st["N"] * (c1 * b_p + c2 * b_f + c3 * 1.0)


def tooth_form(g: dict, i: int) -> dict:
    """ISO 6336-3 method B: Y_F, Y_S of member i, cut by the basic rack (h_fP*, ρ_fP*), external gear."""
    mn, an, x = g["mn"], g["an"], g["x"][i]
    h_fp, r_fp = g["hf"] * mn, g["rho_f"] * mn
    zn = virtual_teeth(g, i)
    e = math.pi / 4 * mn - h_fp * math.tan(an) - (1 - math.sin(an)) * r_fp / math.cos(an)
    gg = r_fp / mn - h_fp / mn + x
    h = 2 / zn * (math.pi / 2 - e / mn) - math.pi / 3
    th = math.pi / 6
    for _ in range(200):                                       # θ = 2G/z_n tan θ − H
        th = 2 * gg / zn * math.tan(th) - h
    s_fn = mn * (zn * math.sin(math.pi / 3 - th) + math.sqrt(3) * (gg / math.cos(th) - r_fp / mn))
    rho_f = r_fp + mn * 2 * gg ** 2 / (math.cos(th) * (zn * math.cos(th) ** 2 - 2 * gg))
    dn = mn * zn
    dbn, dan = dn * math.cos(an), dn + g["da"][i] - g["d"][i]
    ean = g["ea"] / math.cos(g["bb"]) ** 2
    pbn = math.pi * mn * math.cos(an)
    den = 2 * math.sqrt((math.sqrt((dan / 2) ** 2 - (dbn / 2) ** 2) - pbn * (ean - 1)) ** 2 + (dbn / 2) ** 2)
    aen = math.acos(dbn / den)
    ge = (0.5 * math.pi + 2 * x * math.tan(an)) / zn + inv(an) - inv(aen)
    afen = aen - ge
    hfe = 0.5 * mn * ((math.cos(ge) - math.sin(ge) * math.tan(afen)) * den / mn - zn * math.cos(math.pi / 3 - th)
                      - gg / math.cos(th) + r_fp / mn)
    yf = 6 * (hfe / mn) * math.cos(afen) / ((s_fn / mn) ** 2 * math.cos(an))
    ell, qs = s_fn / hfe, s_fn / (2 * rho_f)
    return dict(Y_F=yf, Y_S=(1.2 + 0.13 * ell) * qs ** (1 / (1.21 + 2.3 / ell)), q_s=qs)


def life_factor(nodes: tuple, n: float) -> float:
    """Log-log interpolation between a life curve's nodes; the end values outside."""
    if n <= nodes[0][0]:
        return nodes[0][1]
    for (n0, v0), (n1, v1) in zip(nodes, nodes[1:], strict=False):
        if n <= n1:
            return math.exp(math.log(v0) + math.log(v1 / v0) * math.log(n / n0) / math.log(n1 / n0))
    return nodes[-1][1]


Z_NT_EH_V = ((1e5, 1.6), (5e7, 1.0), (1e10, 0.85))
Y_NT = {"Eh": ((1e3, 2.5), (3e6, 1.0), (1e10, 0.85)), "V": ((1e4, 2.5), (3e6, 1.0), (1e10, 0.85))}


def rate(g: dict, mats: tuple, rz_flank: tuple, rz_root: tuple, *, k_a: float, k_hb: float, k_v: float,
         k_ha: float, life_h: float, nu40: float, s_hmin: float, s_fmin: float) -> dict:
    """ISO 6336-2/-3 method B. ``mats``: per member {t: "Eh" | "V", hlim, flim, hv (optional)}."""
    be, bb, awt, at, ea, eb = g["be"], g["bb"], g["awt"], g["at"], g["ea"], g["eb"]
    z1, z2 = g["z"]
    u, b, mn = g["u"], g["bmin"], g["mn"]
    z_h = math.sqrt(2 * math.cos(bb) * math.cos(awt) / (math.cos(at) ** 2 * math.sin(awt)))
    z_e = math.sqrt(g["e_star"] / math.pi)
    z_eps = math.sqrt((4 - ea) / 3 * (1 - eb) + eb / ea) if eb < 1 else math.sqrt(1 / ea)
    z_beta = 1 / math.sqrt(math.cos(be))
    s_h0 = z_h * z_e * z_eps * z_beta * math.sqrt(g["ft"] / (g["d"][0] * b) * (u + 1) / u)
    s_h = s_h0 * math.sqrt(k_a * k_v * k_hb * k_ha)
    ra = [math.sqrt(g["da"][i] ** 2 / g["db"][i] ** 2 - 1) for i in (0, 1)]
    m1 = math.tan(awt) / math.sqrt((ra[0] - 2 * math.pi / z1) * (ra[1] - (ea - 1) * 2 * math.pi / z2))
    m2 = math.tan(awt) / math.sqrt((ra[1] - 2 * math.pi / z2) * (ra[0] - (ea - 1) * 2 * math.pi / z1))
    z_bd = [1.0 if eb >= 1 else max(1.0, m - eb * (m - 1)) for m in (m1, m2)]
    hlim = min(m["hlim"] for m in mats)                        # the softer member's σ_Hlim sets C_ZL, C_ZR
    c_zl = 0.83 if hlim < 850 else (hlim / 4375 + 0.6357 if hlim <= 1200 else 0.91)
    z_l = c_zl + 4 * (1 - c_zl) / (1.2 + 134 / nu40) ** 2
    v = math.pi * g["d"][0] * g["n1"] / 60000
    c_zv = c_zl + 0.02
    z_v = c_zv + 2 * (1 - c_zv) / math.sqrt(0.8 + 32 / v)
    rho = [0.5 * g["db"][i] * math.tan(awt) for i in (0, 1)]
    rz10 = 0.5 * (rz_flank[0] + rz_flank[1]) * (10 / (rho[0] * rho[1] / (rho[0] + rho[1]))) ** (1 / 3)
    c_zr = 0.15 if hlim < 850 else (0.32 - 0.0002 * hlim if hlim <= 1200 else 0.08)
    z_r = (3 / rz10) ** c_zr
    z_w = [1.0, 1.0]
    for i in (0, 1):                                           # a soft member run with a case-hardened mate
        if mats[i]["t"] != "Eh" and mats[1 - i]["t"] == "Eh" and mats[i].get("hv"):
            z_w[i] = 1.2 - (min(max(0.95 * mats[i]["hv"], 130), 470) - 130) / 1700
    y_beta = 1 - min(eb, 1.0) * min(math.degrees(be), 30) / 120
    depth = max((g["da"][i] - g["df"][i]) / 2 for i in (0, 1))
    bh = b / depth
    k_fb = k_hb ** (bh ** 2 / (1 + bh + bh ** 2))
    out = dict(Z_H=z_h, Z_E=z_e, Z_eps=z_eps, Z_beta=z_beta, sigma_H0_MPa=s_h0, sigma_H_MPa=s_h, Z_L=z_l, Z_V=z_v,
               Z_R=z_r, Y_beta=y_beta, K_Fbeta=k_fb, v=v)
    speeds = (g["n1"], g["n1"] * z1 / z2)
    for i, name in enumerate(("pinion", "gear")):
        m = mats[i]
        n_l = 60 * speeds[i] * life_h
        z_nt = life_factor(Z_NT_EH_V, n_l)
        s_hm = s_h * z_bd[i]
        s_hg = m["hlim"] * z_nt * z_l * z_v * z_r * z_w[i]
        tf = tooth_form(g, i)
        s_f0 = g["ft"] / (min(g["b"][i], b + 2 * mn) * mn) * tf["Y_F"] * tf["Y_S"] * y_beta
        s_f = s_f0 * k_a * k_v * k_fb * 1.0                     # K_Fα = 1 (checked separately)
        rho_slip = 0.0030 if m["t"] == "Eh" else 0.0194
        y_d = (1 + math.sqrt(rho_slip * (1 + 2 * tf["q_s"]) / 5)) / (1 + math.sqrt(rho_slip * 1.2))
        y_r = 1.674 - 0.529 * (rz_root[i] + 1) ** 0.1
        y_x = 1.0 if mn <= 5 else (max(0.8, 1.05 - 0.01 * mn) if m["t"] == "Eh" else max(0.85, 1.03 - 0.006 * mn))
        y_nt = life_factor(Y_NT[m["t"]], n_l)
        s_fg = m["flim"] * 2.0 * y_nt * y_d * y_r * y_x
        out[name] = dict(load_cycles=n_l, Z_BD=z_bd[i], sigma_H_MPa=s_hm, Z_NT=z_nt, sigma_HG_MPa=s_hg,
                         sigma_HP_MPa=s_hg / s_hmin, S_H=s_hg / s_hm, Y_F=tf["Y_F"], Y_S=tf["Y_S"], sigma_F0_MPa=s_f0,
                         sigma_F_MPa=s_f, Y_delta_rel_T=y_d, Y_R_rel_T=y_r, Y_X=y_x, Y_NT=y_nt, sigma_FG_MPa=s_fg,
                         sigma_FP_MPa=s_fg / s_fmin, S_F=s_fg / s_f, Z_W=z_w[i])
    return out


def tip_thickness(g: dict, i: int) -> float:
    """Normal tooth thickness on the tip circle: s_at = d_a (s_t/d + inv α_t − inv α_at), s_an = s_at cos β_a."""
    s_t = g["mt"] * (math.pi / 2 + 2 * g["x"][i] * math.tan(g["an"]))
    a_at = math.acos(g["db"][i] / g["da"][i])
    s_at = g["da"][i] * (s_t / g["d"][i] + inv(g["at"]) - inv(a_at))
    beta_a = math.atan(math.tan(g["be"]) * g["da"][i] / g["d"][i])
    return s_at * math.cos(beta_a)
