"""ISO 6336:2006 method B for an external gear pair, written out by hand for the reference tests.

Independent of gearcli's rating code: every formula is typed here again from the standard's clauses (as
docs/iso6336.md quotes them, and as ISO 6336-1/-2/-3/-5:2006 print them), in the standard's units (mm, µm,
N/mm², m/s). Only the geometry the design computes (tips, roots, ε_α, α_wt) is recomputed too (ISO 21771), so a
test compares whole chains: input file → factors → stresses → safeties.

Scope: solid blanks, ISO 53 basic rack (or the given one), x from the file, C_a tip relief, K_Hβ given or by
method C (pinion centred between bearings, no lead correction), no allowances.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

SURFACE = {"case_carburized", "nitrided", "nitrocarburized", "induction_hardened", "flame_hardened"}


def inv(a: float) -> float:
    return math.tan(a) - a


@dataclass
class Member:
    z: int
    b: float  # face width, mm
    treatment: str
    hlim: float  # σ_Hlim
    flim: float  # σ_Flim
    rz_flank: float
    rz_root: float
    x: float = 0.0
    hv: float | None = None
    e_mod: float = 206000.0
    nu: float = 0.3
    rho: float = 7.85e-6  # kg/mm³


@dataclass
class Pair:
    p: Member  # ISO's pinion: the smaller wheel, driving here
    g: Member
    mn: float
    alpha_n_deg: float
    beta_deg: float
    grade: int
    torque_pinion_Nm: float
    n1_rpm: float
    k_a: float
    nu40: float
    life_h: float
    c_a: float = 0.0
    k_hbeta: float | None = None
    rack: tuple[float, float, float] = (1.0, 1.25, 0.38)
    quality: str = "normal"
    s_hmin: float = 1.0
    s_fmin: float = 1.4
    out: dict = field(default_factory=dict)


# ------------------------------------------------------------------------------------ ISO 21771
def geometry(q: Pair) -> dict:
    an, beta = math.radians(q.alpha_n_deg), math.radians(q.beta_deg)
    at = math.atan(math.tan(an) / math.cos(beta))
    mt = q.mn / math.cos(beta)
    z1, z2, x1, x2 = q.p.z, q.g.z, q.p.x, q.g.x
    d1, d2 = z1 * mt, z2 * mt
    db1, db2 = d1 * math.cos(at), d2 * math.cos(at)
    target = inv(at) + 2.0 * math.tan(an) * (x1 + x2) / (z1 + z2)
    awt = at
    for _ in range(100):  # Newton on inv α_wt = target
        awt -= (inv(awt) - target) / math.tan(awt) ** 2
    a = 0.5 * (d1 + d2)
    aw = a * math.cos(at) / math.cos(awt)
    k = (aw - a) / q.mn - (x1 + x2)
    ha, hf, _ = q.rack
    da1, da2 = d1 + 2 * q.mn * (ha + x1 + k), d2 + 2 * q.mn * (ha + x2 + k)
    df1, df2 = d1 - 2 * q.mn * (hf - x1), d2 - 2 * q.mn * (hf - x2)
    bb = math.atan(math.tan(beta) * math.cos(at))
    ea = (0.5 * math.sqrt(da1 ** 2 - db1 ** 2) + 0.5 * math.sqrt(da2 ** 2 - db2 ** 2) - aw * math.sin(awt)) \
        / (math.pi * mt * math.cos(at))
    b = min(q.p.b, q.g.b)
    eb = b * math.sin(beta) / (math.pi * q.mn)
    return dict(an=an, beta=beta, at=at, awt=awt, mt=mt, d=(d1, d2), db=(db1, db2), da=(da1, da2), df=(df1, df2),
                bb=bb, ea=ea, eb=eb, eg=ea + eb, aw=aw, b=b)


# ------------------------------------------------------------------------------------ ISO 6336-1
C_Q = (0.04723, 0.15551, 0.25791, -0.00635, -0.11654, -0.00193, -0.24188, 0.00529, 0.00182)


def stiffness(q: Pair, g: dict, line_load: float) -> dict:
    zn = [m.z / (math.cos(g["bb"]) ** 2 * math.cos(g["beta"])) for m in (q.p, q.g)]
    x1, x2 = q.p.x, q.g.x
    c = C_Q
    qp = (c[0] + c[1] / zn[0] + c[2] / zn[1] + c[3] * x1 + c[4] * x1 / zn[0] + c[5] * x2 + c[6] * x2 / zn[1]
          + c[7] * x1 ** 2 + c[8] * x2 ** 2)
    c_b = (1 + 0.5 * (1.2 - q.rack[1])) * (1 - 0.02 * (20 - q.alpha_n_deg))
    cp = (1 / qp) * 0.8 * 1.0 * c_b * math.cos(g["beta"])
    if line_load < 100:
        cp *= (line_load / 100) ** 0.25
    cga = cp * (0.75 * g["ea"] + 0.25)
    return dict(zn=zn, cp=cp, cga=cga, cgb=0.85 * cga)


def resonance(q: Pair, g: dict, cga: float, line_load: float) -> dict:
    """m_red from the two solid discs of d_m = (d_a + d_f)/2 (m* = π ρ d_m⁴ / (8 d_b²)), n_E1, N, N_S."""
    ms = [math.pi * m.rho * ((da + df) / 2) ** 4 / (8 * db ** 2)
          for m, da, df, db in zip((q.p, q.g), g["da"], g["df"], g["db"], strict=True)]
    m_red = ms[0] * ms[1] / (ms[0] + ms[1])
    n_e1 = 30000 / (math.pi * q.p.z) * math.sqrt(cga / m_red)
    n_s = 0.5 + 0.35 * math.sqrt(line_load / 100) if line_load < 100 else 0.85
    return dict(m_red=m_red, n_e1=n_e1, N=q.n1_rpm / n_e1, N_S=n_s)


D_LIM = (5, 20, 50, 125, 280, 560, 1000, 1600, 2500, 4000, 6000, 8000, 10000)
M_LIM = (0.5, 2, 3.5, 6, 10, 16, 25, 40, 70)
B_LIM = (4, 10, 20, 40, 80, 160, 250, 400, 650, 1000)


def _gm(v: float, lims: tuple) -> float:
    for lo, hi in zip(lims, lims[1:], strict=False):
        if v <= hi:
            return math.sqrt(lo * hi)
    return math.sqrt(lims[-2] * lims[-1])


def _round_1328(v: float) -> float:
    return float(round(v)) if v > 10 else (round(2 * v) / 2 if v >= 5 else round(v, 1))


def tolerances(d: float, m: float, b: float, grade: int) -> tuple[float, float, float]:
    """f_pt, f_fα, f_Hβ of ISO 1328-1:1995 (class-5 formulas at the range means, × 2^((Q−5)/2), rounded)."""
    s = 2 ** ((grade - 5) / 2)
    dm, mm, bm = _gm(d, D_LIM), _gm(m, M_LIM), _gm(b, B_LIM)
    return (_round_1328((0.3 * (mm + 0.4 * math.sqrt(dm)) + 4) * s),
            _round_1328((2.5 * math.sqrt(mm) + 0.17 * math.sqrt(dm) + 0.5) * s),
            _round_1328((0.07 * math.sqrt(dm) + 0.45 * math.sqrt(bm) + 3) * s))


def y_alpha(m: Member, f: float, v: float) -> float:
    if m.treatment in SURFACE:
        return min(0.075 * f, 3.0)
    if m.treatment == "grey_iron":
        return min(0.275 * f, math.inf if v <= 5 else 22 if v <= 10 else 11)
    return min(160 / m.hlim * f, math.inf if v <= 5 else (12800 if v <= 10 else 6400) / m.hlim)


def y_beta(m: Member, fbx: float, v: float) -> float:
    if m.treatment in SURFACE:
        return min(0.15 * fbx, 6.0)
    if m.treatment == "grey_iron":
        return min(0.55 * fbx, math.inf if v <= 5 else 45 if v <= 10 else 22)
    return min(320 / m.hlim * fbx, math.inf if v <= 5 else (25600 if v <= 10 else 12800) / m.hlim)


def cv(eg: float) -> tuple:
    if eg <= 2:
        c2, c3, c4, c6 = 0.34, 0.23, 0.90, 0.47
    else:
        c2, c3, c4, c6 = 0.57 / (eg - 0.3), 0.096 / (eg - 1.56), (0.57 - 0.05 * eg) / (eg - 1.44), 0.12 / (eg - 1.74)
    c7 = 0.75 if eg <= 1.5 else (0.125 * math.sin(math.pi * (eg - 2)) + 0.875 if eg <= 2.5 else 1.0)
    return 0.32, c2, c3, c4, 0.47, c6, c7


def k_v_method_b(res: dict, eg: float, cp: float, line_load: float, fpb_eff: float, ffa_eff: float, c_a: float):
    c1, c2, c3, c4, c5, c6, c7 = cv(eg)
    bp, bf, bk = cp * fpb_eff / line_load, cp * ffa_eff / line_load, abs(1 - cp * c_a / line_load)
    n = res["N"]
    sub = n * (c1 * bp + c2 * bf + c3 * bk) + 1
    main = c1 * bp + c2 * bf + c4 * bk + 1
    sup = c5 * bp + c6 * bf + c7
    if n <= res["N_S"]:
        return sub, "subcritical"
    if n <= 1.15:
        return main, "main"
    if n >= 1.5:
        return sup, "supercritical"
    return sup + (main - sup) * (1.5 - n) / 0.35, "intermediate"


# ------------------------------------------------------------------------------------ ISO 6336-3 root
def tooth_form(m: Member, q: Pair, g: dict, i: int) -> dict:
    mn, an = q.mn, g["an"]
    hfp, rfp = q.rack[1] * mn, q.rack[2] * mn
    zn = m.z / (math.cos(g["bb"]) ** 2 * math.cos(g["beta"]))
    e = math.pi / 4 * mn - hfp * math.tan(an) - (1 - math.sin(an)) * rfp / math.cos(an)
    gg = rfp / mn - hfp / mn + m.x
    h = 2 / zn * (math.pi / 2 - e / mn) - math.pi / 3
    th = math.pi / 6
    for _ in range(200):
        th = 2 * gg / zn * math.tan(th) - h
    sfn = mn * (zn * math.sin(math.pi / 3 - th) + math.sqrt(3) * (gg / math.cos(th) - rfp / mn))
    rf = rfp + mn * 2 * gg ** 2 / (math.cos(th) * (zn * math.cos(th) ** 2 - 2 * gg))
    dn = mn * zn
    dbn = dn * math.cos(an)
    dan = dn + g["da"][i] - g["d"][i]
    ean = g["ea"] / math.cos(g["bb"]) ** 2
    pbn = math.pi * mn * math.cos(an)  # = π d cos β cos α_n / z
    den = 2 * math.sqrt((math.sqrt((dan / 2) ** 2 - (dbn / 2) ** 2) - pbn * (ean - 1)) ** 2 + (dbn / 2) ** 2)
    aen = math.acos(dbn / den)
    ge = (math.pi / 2 + 2 * m.x * math.tan(an)) / zn + inv(an) - inv(aen)
    afen = aen - ge
    hfe = mn / 2 * ((math.cos(ge) - math.sin(ge) * math.tan(afen)) * den / mn - zn * math.cos(math.pi / 3 - th)
                    - gg / math.cos(th) + rfp / mn)
    yf = 6 * hfe / mn * math.cos(afen) / ((sfn / mn) ** 2 * math.cos(an))
    L = sfn / hfe
    qs = sfn / (2 * rf)
    ys = (1.2 + 0.13 * L) * qs ** (1 / (1.21 + 2.3 / L))
    return dict(Y_F=yf, Y_S=ys, q_s=qs, s_Fn=sfn, rho_F=rf, h_Fe=hfe)


# ------------------------------------------------------------------------------------ life curves
ZNT = {"steel": ((1e5, 1.6), (5e7, 1.0), (1e10, 0.85)), "nitr": ((1e5, 1.3), (2e6, 1.0), (1e10, 0.85)),
       "nc": ((1e5, 1.1), (2e6, 1.0), (1e10, 0.85))}
YNT = {"through": ((1e4, 2.5), (3e6, 1.0), (1e10, 0.85)), "surface": ((1e3, 2.5), (3e6, 1.0), (1e10, 0.85)),
       "nitr": ((1e3, 1.6), (3e6, 1.0), (1e10, 0.85)), "nc": ((1e3, 1.1), (3e6, 1.0), (1e10, 0.85))}


def _loglog(nodes, n: float, optimum: bool) -> float:
    if n <= nodes[0][0]:
        return nodes[0][1]
    if optimum and n >= nodes[1][0]:
        return 1.0
    for (na, ya), (nb, yb) in zip(nodes, nodes[1:], strict=False):
        if n <= nb:
            return 10 ** (math.log10(ya) + (math.log10(yb) - math.log10(ya)) * math.log10(n / na) / math.log10(nb / na))
    return nodes[-1][1]


def z_nt(t: str, n: float, optimum: bool = False) -> float:
    key = "nitr" if t in ("nitrided", "grey_iron") else "nc" if t == "nitrocarburized" else "steel"
    return _loglog(ZNT[key], n, optimum)


def y_nt(t: str, n: float, optimum: bool = False) -> float:
    key = ("surface" if t in ("case_carburized", "induction_hardened", "flame_hardened") else
           "nitr" if t in ("nitrided", "grey_iron") else "nc" if t == "nitrocarburized" else "through")
    return _loglog(YNT[key], n, optimum)


SLIP = {"case_carburized": 0.0030, "induction_hardened": 0.0030, "flame_hardened": 0.0030, "nitrided": 0.1005,
        "nitrocarburized": 0.1005, "through_hardened": 0.0194, "cast_steel": 0.0194, "nodular_iron": 0.0194,
        "structural_steel": 0.0445, "grey_iron": 0.3095}


def y_rrelt(t: str, rz: float) -> float:
    if t == "structural_steel":
        return 1.070 if rz < 1 else 5.306 - 4.203 * (min(rz, 40) + 1) ** 0.01
    if t in ("grey_iron", "nitrided", "nitrocarburized"):
        return 1.025 if rz < 1 else 4.299 - 3.259 * (min(rz, 40) + 1) ** 0.0058
    return 1.120 if rz < 1 else 1.674 - 0.529 * (min(rz, 40) + 1) ** 0.1


def y_x(t: str, mn: float) -> float:
    if mn <= 5:
        return 1.0
    if t in SURFACE:
        return max(1.05 - 0.01 * mn, 0.8)
    if t == "grey_iron":
        return max(1.075 - 0.015 * mn, 0.7)
    return max(1.03 - 0.006 * mn, 0.85)


def c_zl(h: float) -> float:
    return 0.83 if h < 850 else (h / 4375 + 0.6357 if h <= 1200 else 0.91)


# ------------------------------------------------------------------------------------ the rating
def rate(q: Pair, k_v_given: float | None = None) -> dict:
    """The whole rating; ``k_v_given`` replaces method B's K_v (a simulated or given dynamic factor), and every
    factor that reads K_v (K_Hβ's estimate, K_Hα, K_Fα) follows it."""
    g = geometry(q)
    b = g["b"]
    d1 = g["d"][0]
    ft = q.torque_pinion_Nm * 1000 / (d1 / 2)
    wl = ft * q.k_a / b  # K_A F_t / b
    s = stiffness(q, g, wl)
    res = resonance(q, g, s["cga"], wl)
    v = math.pi * d1 * q.n1_rpm / 60000
    tol = [tolerances(d, q.mn, b, q.grade) for d in g["d"]]
    fpb = max(t[0] for t in tol) * math.cos(g["at"])
    ffa = max(t[1] for t in tol)
    ya = 0.5 * (y_alpha(q.p, fpb, v) + y_alpha(q.g, fpb, v))
    yf = 0.5 * (y_alpha(q.p, ffa, v) + y_alpha(q.g, ffa, v))
    k_v, rng = k_v_method_b(res, g["eg"], s["cp"], wl, fpb - ya, ffa - yf, q.c_a)
    if k_v_given is not None:
        k_v = k_v_given
    fm = wl * k_v  # F_m / b
    if q.k_hbeta is None:
        fhb = tolerances(d1, q.mn, b, q.grade)[2]
        fsh = 0.023 * fm * (b / d1) ** 2
        fbx = max(1.33 * fsh + fhb, 0.005 * fm, 0.5 * fhb)
        yb = 0.5 * (y_beta(q.p, fbx, v) + y_beta(q.g, fbx, v))  # ISO 6336-1:2006, 7.6: the mean of both members
        fby = fbx - yb
        khb = 1 + s["cgb"] * fby / (2 * fm)
        if khb > 2:
            khb = math.sqrt(2 * s["cgb"] * fby / fm)
    else:
        khb = q.k_hbeta
    # h: the tooth depth (d_a - d_f)/2, the deeper member's (both (h_aP* + h_fP* + k) m_n here: the tip alteration k
    # shortens it), as ISO 6336-1 7.7 and the published reports (KISSsoft, ISO/TR 6336-30) take it
    depth = 0.5 * max(g["da"][i] - g["df"][i] for i in (0, 1))
    bh = max(b / depth, 3.0)
    kfb = khb ** (bh ** 2 / (1 + bh + bh ** 2))
    ea, eb, eg = g["ea"], g["eb"], g["eg"]
    z_eps = math.sqrt(1 / ea) if eb >= 1 else math.sqrt((4 - ea) / 3 * (1 - eb) + eb / ea)
    fth = fm * khb
    feff = max(fpb, ffa) - ya
    kk = (eg / 2 * (0.9 + 0.4 * s["cga"] * feff / fth) if eg <= 2 else
          0.9 + 0.4 * math.sqrt(2 * (eg - 1) / eg) * s["cga"] * feff / fth)
    kha = min(max(kk, 1.0), eg / (ea * z_eps ** 2))
    kfa = min(max(kk, 1.0), eg / (0.25 * ea + 0.75))
    # ISO 6336-2
    z_h = math.sqrt(2 * math.cos(g["bb"]) * math.cos(g["awt"]) / (math.cos(g["at"]) ** 2 * math.sin(g["awt"])))
    z_e = math.sqrt(1 / (math.pi * ((1 - q.p.nu ** 2) / q.p.e_mod + (1 - q.g.nu ** 2) / q.g.e_mod)))
    z_b = 1 / math.sqrt(math.cos(g["beta"]))
    u = q.g.z / q.p.z
    s_h0 = z_h * z_e * z_eps * z_b * math.sqrt(ft / (d1 * b) * (u + 1) / u)
    s_h = s_h0 * math.sqrt(q.k_a * k_v * khb * kha)
    roll = [math.sqrt((da / db) ** 2 - 1) for da, db in zip(g["da"], g["db"], strict=True)]
    zs = (q.p.z, q.g.z)
    zbd = []
    for i, j in ((0, 1), (1, 0)):
        mm = math.tan(g["awt"]) / math.sqrt((roll[i] - 2 * math.pi / zs[i]) * (roll[j] - (ea - 1) * 2 * math.pi / zs[j]))
        zbd.append(1.0 if eb >= 1 else max(1.0, mm - eb * (mm - 1)))
    h_low = min(q.p.hlim, q.g.hlim)
    czl = c_zl(h_low)
    z_l = czl + 4 * (1 - czl) / (1.2 + 134 / q.nu40) ** 2
    z_v = czl + 0.02 + 2 * (1 - czl - 0.02) / math.sqrt(0.8 + 32 / v)
    rho = [0.5 * db * math.tan(g["awt"]) for db in g["db"]]
    rho_red = rho[0] * rho[1] / (rho[0] + rho[1])
    rz10 = 0.5 * (q.p.rz_flank + q.g.rz_flank) * (10 / rho_red) ** (1 / 3)
    czr = 0.15 if h_low < 850 else (0.32 - 0.0002 * h_low if h_low <= 1200 else 0.08)
    z_r = (3 / rz10) ** czr
    hard = [m.treatment in SURFACE for m in (q.p, q.g)]
    z_w = [1.0, 1.0]
    if hard[0] != hard[1]:
        soft = 1 if hard[0] else 0
        hv = (q.p, q.g)[soft].hv
        if hv is not None:
            hb = min(max(0.95 * hv, 130), 470)
            z_w[soft] = 1.2 - (hb - 130) / 1700
    y_b = 1 - min(eb, 1) * min(q.beta_deg, 30) / 120
    ean = ea / math.cos(g["bb"]) ** 2  # Y_DT (ISO 6336-3:2006, 11): grade ≤ 4 and ε_αn > 2.05 only
    y_dt = 1.0 if q.grade > 4 or ean <= 2.05 else (-0.666 * ean + 2.366 if ean <= 2.5 else 0.7)
    out = dict(g=g, s=s, res=res, v=v, F_t=ft, f_pb=fpb, f_fa=ffa, y_a=ya, y_f=yf, K_v=k_v, range=rng, K_Hbeta=khb,
               K_Fbeta=kfb, K_Halpha=kha, K_Falpha=kfa, Z_eps=z_eps, Z_H=z_h, Z_E=z_e, Z_beta=z_b, sigma_H0=s_h0,
               sigma_H=s_h, Z_L=z_l, Z_V=z_v, Z_R=z_r, Z_W=max(z_w), Y_beta=y_b)
    for i, m in enumerate((q.p, q.g)):
        n_l = 60 * q.n1_rpm * (q.p.z / m.z) * q.life_h
        znt = z_nt(m.treatment, n_l, q.quality == "optimum")
        shg = m.hlim * znt * z_l * z_v * z_r * z_w[i]
        form = tooth_form(m, q, g, i)
        bf = min(m.b, b + 2 * q.mn)
        sf0 = ft / (bf * q.mn) * form["Y_F"] * form["Y_S"] * y_b * y_dt
        sf = sf0 * q.k_a * k_v * kfb * kfa
        rho_s = SLIP[m.treatment]
        yd = (1 + math.sqrt(rho_s * (1 + 2 * form["q_s"]) / 5)) / (1 + math.sqrt(rho_s * 1.2))
        yr = y_rrelt(m.treatment, m.rz_root)
        yx = y_x(m.treatment, q.mn)
        ynt = y_nt(m.treatment, n_l, q.quality == "optimum")
        sfg = m.flim * 2 * ynt * yd * yr * yx
        out[("pinion", "gear")[i]] = dict(
            load_cycles=n_l, Z_BD=zbd[i], sigma_H=zbd[i] * s_h, Z_NT=znt, sigma_HG=shg, S_H=shg / (zbd[i] * s_h),
            Y_F=form["Y_F"], Y_S=form["Y_S"], Y_DT=y_dt, q_s=form["q_s"], sigma_F0=sf0, sigma_F=sf, Y_delta_rel_T=yd,
            Y_R_rel_T=yr, Y_X=yx, Y_NT=ynt, sigma_FG=sfg, S_F=sfg / sf, Z_W=z_w[i])
    return out


def toml_doc(q: Pair, *, extra_rating: dict | None = None) -> dict:
    """The design file (as a dict) of the pair: the pinion drives at n1 with the output torque T1 u."""
    def member(m: Member, hand: str) -> dict:
        d = {"teeth": m.z, "face_width_mm": m.b, "material": f"m{m.z}", "profile_shift": m.x,
             "flank_roughness_Rz_um": m.rz_flank, "root_roughness_Rz_um": m.rz_root}
        if q.beta_deg > 0:
            d["hand"] = hand
        return d

    def material(m: Member) -> dict:
        d = {"density_kg_m3": m.rho * 1e9, "youngs_modulus_MPa": m.e_mod, "poisson_ratio": m.nu,
             "treatment": m.treatment, "contact_fatigue_limit_MPa": m.hlim, "bending_fatigue_limit_MPa": m.flim}
        if m.hv is not None:
            d["surface_hardness_HV"] = m.hv
        return d

    stage = {"normal_module_mm": q.mn, "normal_pressure_angle_deg": q.alpha_n_deg, "helix_angle_deg": q.beta_deg,
             "accuracy_grade": q.grade, "pinion": member(q.p, "left"), "gear": member(q.g, "right"),
             "basic_rack": {"addendum": q.rack[0], "dedendum": q.rack[1], "root_radius": q.rack[2]}}
    if q.c_a:
        stage["tip_relief_um"] = q.c_a
    rating = {"required_life_h": q.life_h, "material_quality": q.quality, "min_safety_pitting": q.s_hmin,
              "min_safety_bending": q.s_fmin, **(extra_rating or {})}
    if q.k_hbeta is not None:
        rating["face_load_factor"] = q.k_hbeta
    return {"materials": {f"m{q.p.z}": material(q.p), f"m{q.g.z}": material(q.g)}, "stage": [stage],
            "input": {"speed_rpm": q.n1_rpm},
            "load": {"torque_Nm": q.torque_pinion_Nm * q.g.z / q.p.z, "application_factor": q.k_a},
            "lubricant": {"viscosity_40C_mm2_s": q.nu40}, "rating": rating}
