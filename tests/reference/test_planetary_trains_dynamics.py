"""The dynamics of the engineer's own planetary trains (tests/reference/test_planetary_trains_hand.py, scene S:
a 22/30/82 planetary with 4 planets, then a helical 19/57 stage), checked against independent references:

- `modes` against a hand-assembled J/K eigenproblem (scipy.linalg.eigh), the carrier held (a star: the ring
  drives the helical pinion) and the sun held (the carrier, with the planets' translational inertia, drives it);
- `simulate`'s rigid limit: stiff linear meshes, the input speed and the load STEP-ramped over 50 ms; every mesh
  force and the input torque follow the rigid drivetrain's Newton-Euler equations written out here (the planets'
  spin in the housing's frame, their mass on the carrier), and settle at the design's static forces;
- the settled window of every arrangement with losses: each planet's sun and ring mesh force, the helical mesh's and
  the input torque equal the design's static values; load sharing 1 with equal spacing;
- the energy record against the channels: input and load work by the trapezoidal rule over the CSV series, the
  kinetic energy from the shaft speeds (the planets' from the kinematics, settled), the strain energy from the
  mesh forces (F_n^2 / 2k of a linear law).

Stated inertias and a linear law (`exponent = 1`, k in N/mm) keep every input of the hand models in the file.
"""

from __future__ import annotations

import io
import json
import math

import numpy as np
import pytest
from numpy.testing import assert_allclose
from scipy.linalg import eigh

from tests.reference.test_planetary_trains_hand import (
    ARRANGEMENTS,
    ETA2,
    N_IN,
    N_PL,
    STAR,
    T_OUT,
    _run,
    _write,
    design,
    star,
)

ALPHA = math.radians(20)
MN = 4e-3
RB_S, RB_P, RB_R = (z * MN / 2 * math.cos(ALPHA) for z in (22, 30, 82))
A_C = (22 + 30) * MN / 2  # the carrier radius, m
BETA2 = math.radians(10)
ALPHA_T2 = math.atan(math.tan(ALPHA) / math.cos(BETA2))
BETA_B2 = math.atan(math.tan(BETA2) * math.cos(ALPHA_T2))
RB_1, RB_2 = (z * 5e-3 / math.cos(BETA2) / 2 * math.cos(ALPHA_T2) for z in (19, 57))
J_SUN, J_PLANET, M_PLANET, J_RING, J_CARRIER, J_PINION2, J_GEAR2 = 0.002, 0.006, 3.5, 0.2, 0.1, 0.004, 0.3
K1, K2 = 5e5, 8e5  # N/mm: the planet meshes' law and the helical mesh's (normal, linear)

LINEAR = f"""
[contact]
stiffness = {K1:g}
exponent = 1
damping_ratio = 0.05
"""


def linear_scene(fixed: str = "carrier", driven: str = "sun", k1: float = K1, k2: float = K2, eta: float = 1.0,
                 ramp: float = 0.0, eta2: float = 1.0) -> str:
    """Scene S with stated inertias and linear meshes (both stages lossless unless given)."""
    text = star(fixed=fixed, driven=driven, eta=eta, contact=LINEAR.replace(f"{K1:g}", f"{k1:g}"),
                extra="[simulation]\nduration_s = 0.1\nsteps = 1000\n")
    inertia = {"sun    = {": J_SUN, "planet = {": J_PLANET, "ring   = {": J_RING, "pinion = {": J_PINION2,
               "gear   = {": J_GEAR2}
    for head, j in inertia.items():
        extra = f" inertia_kg_m2 = {j}," + (f" mass_kg = {M_PLANET}," if head.startswith("planet") else "")
        text = text.replace(head, head + extra, 1)
    text = text.replace(f"efficiency = {ETA2}", f"efficiency = {eta2}", 1)
    text = text.replace('fixed = "', f"carrier = {{ inertia_kg_m2 = {J_CARRIER} }}\nfixed = \"", 1)
    text = text.replace("gear   = {", f"mesh = {{ stiffness = {k2:g}, exponent = 1 }}\ngear   = {{", 1)
    if ramp:
        text = text.replace(f"speed_rpm = {N_IN}\n", f"speed_rpm = {N_IN}\nramp_s = {ramp}\n")
        text = text.replace(f"torque_Nm = {T_OUT}\n", f"torque_Nm = {T_OUT}\nramp_s = {ramp}\n")
    return text


def run_json(tmp_path, command: str, text: str) -> dict:
    res = _run(command, str(_write(tmp_path, text)), "--format", "json")
    assert res.exit_code == 0, res.stderr
    return json.loads(res.stdout)


def run_csv(tmp_path, text: str):
    res = _run("simulate", str(_write(tmp_path, text)), "--format", "csv")
    assert res.exit_code == 0, res.stderr
    return np.genfromtxt(io.StringIO(res.stdout), delimiter=",", names=True)


def _hand_frequencies(k: np.ndarray, m: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    free = np.sqrt(np.abs(eigh(k, m, eigvals_only=True))) / (2 * math.pi)
    clamped = np.sqrt(eigh(k[1:, 1:], m[1:, 1:], eigvals_only=True)) / (2 * math.pi)  # the input body held
    return free, clamped


def _tool_frequencies(data: dict) -> dict[str, list[float]]:
    return {b: sorted(x["frequency_Hz"] for x in modes) for b, modes in data["boundaries"].items()}


# ----------------------------------------------------------------------------------------------------- modes
def test_star_modes_against_a_hand_assembled_eigenproblem(tmp_path):
    """Carrier held. Coordinates: the sun, the planets (absolute, the sun's sense), the ring's shaft with the helical
    pinion (its running sense, against the sun's) and the gear. Sun mesh d = r_bs th_s + r_bp th_p; ring mesh
    d = -r_bp th_p - r_br phi (the ring's absolute angle is -phi); helical d = r_b1 phi - r_b2 th_g along the
    transverse line of action, with the normal stiffness's transverse share k cos^2 beta_b. K = sum k v v^T."""
    data = run_json(tmp_path, "modes", linear_scene("carrier", "sun"))
    n = N_PL + 3
    k = np.zeros((n, n))
    for j in range(N_PL):
        for v_idx, v_val in (((0, 1 + j), (RB_S, RB_P)), ((1 + j, N_PL + 1), (-RB_P, -RB_R))):
            v = np.zeros(n)
            v[list(v_idx)] = v_val
            k += K1 * 1e3 * np.outer(v, v)
    v = np.zeros(n)
    v[[N_PL + 1, N_PL + 2]] = RB_1, -RB_2
    k += K2 * 1e3 * math.cos(BETA_B2) ** 2 * np.outer(v, v)
    m = np.diag([J_SUN, *[J_PLANET] * N_PL, J_RING + J_PINION2, J_GEAR2])
    free, clamped = _hand_frequencies(k, m)
    got = _tool_frequencies(data)
    assert_allclose(got["clamped_input"], clamped, rtol=1e-9)
    assert_allclose(got["free"][1:], free[1:], rtol=1e-9)
    assert got["free"][0] == 0.0
    # the planets' (N - 1)-fold mode: sun and ring still, w^2 = 2 k r_bp^2 / J_p
    planet = math.sqrt(2 * K1 * 1e3 * RB_P**2 / J_PLANET) / (2 * math.pi)
    assert_allclose([f for f in got["clamped_input"] if abs(f / planet - 1) < 1e-6], [planet] * (N_PL - 1),
                    rtol=1e-9)


def test_sun_held_modes_against_a_hand_assembled_eigenproblem(tmp_path):
    """Sun held, ring driven, the carrier (own inertia + N m_p a^2 + the helical pinion) out. Coordinates (absolute):
    ring, planets, carrier, gear. Sun mesh d = r_bs (0 - th_c) + r_bp (th_p - th_c); ring mesh
    d = r_br (th_r - th_c) - r_bp (th_p - th_c) (the carrier frame's fixed-axis kinematics)."""
    data = run_json(tmp_path, "modes", linear_scene("sun", "ring"))
    n, c = N_PL + 3, N_PL + 1
    k = np.zeros((n, n))
    for j in range(N_PL):
        v = np.zeros(n)
        v[1 + j], v[c] = RB_P, -(RB_S + RB_P)
        k += K1 * 1e3 * np.outer(v, v)
        v = np.zeros(n)
        v[0], v[1 + j], v[c] = RB_R, -RB_P, RB_P - RB_R
        k += K1 * 1e3 * np.outer(v, v)
    v = np.zeros(n)
    v[[c, c + 1]] = RB_1, -RB_2
    k += K2 * 1e3 * math.cos(BETA_B2) ** 2 * np.outer(v, v)
    m = np.diag([J_RING, *[J_PLANET] * N_PL, J_CARRIER + N_PL * M_PLANET * A_C**2 + J_PINION2, J_GEAR2])
    free, clamped = _hand_frequencies(k, m)
    got = _tool_frequencies(data)
    assert_allclose(got["clamped_input"], clamped, rtol=1e-9)
    assert_allclose(got["free"][1:], free[1:], rtol=1e-9)


def test_star_modes_with_losses_against_the_hand_loss_law(tmp_path):
    """eta 0.97 on the planetary (eta_m = sqrt 0.97 per mesh, the carrier held: eta_0 = eta), 0.98 on the helical
    stage. `modes` linearises the right-hand side `simulate` integrates (DESIGN section 13), whose loss law
    (docs/planetary.md) puts the spring force F = k d on a mesh's driving side and eta_m F on its driven side: the sun
    mesh's planet side, the ring mesh's ring side (the planet drives the ring), the helical gear's side. K is then
    not symmetric, K = sum k q g^T with g the lever vector of d and q the sides' levers; scipy.linalg.eig."""
    from scipy.linalg import eig

    data = run_json(tmp_path, "modes", linear_scene("carrier", "sun", eta=0.97, eta2=0.98))
    eta_m = math.sqrt(0.97)
    n = N_PL + 3
    k = np.zeros((n, n))
    for j in range(N_PL):
        g, q = np.zeros(n), np.zeros(n)
        g[[0, 1 + j]] = RB_S, RB_P
        q[[0, 1 + j]] = RB_S, eta_m * RB_P
        k += K1 * 1e3 * np.outer(q, g)
        g, q = np.zeros(n), np.zeros(n)
        g[[1 + j, N_PL + 1]] = -RB_P, -RB_R
        q[[1 + j, N_PL + 1]] = -RB_P, -eta_m * RB_R
        k += K1 * 1e3 * np.outer(q, g)
    g, q = np.zeros(n), np.zeros(n)
    g[[N_PL + 1, N_PL + 2]] = RB_1, -RB_2
    q[[N_PL + 1, N_PL + 2]] = RB_1, -0.98 * RB_2
    k += K2 * 1e3 * math.cos(BETA_B2) ** 2 * np.outer(q, g)
    m = np.diag([J_SUN, *[J_PLANET] * N_PL, J_RING + J_PINION2, J_GEAR2])
    lam = eig(k[1:, 1:], m[1:, 1:], right=False)
    assert_allclose(lam.imag, 0.0, atol=1e-6 * abs(lam).max())
    clamped = np.sort(np.sqrt(lam.real)) / (2 * math.pi)
    assert_allclose(_tool_frequencies(data)["clamped_input"], clamped, rtol=1e-9)


# ----------------------------------------------------------------------------------------------- rigid limit
def _step(t: np.ndarray, t1: float, h1: float) -> np.ndarray:
    s = np.clip(t / t1, 0.0, 1.0)
    return h1 * s * s * (3 - 2 * s)


TR, W0, TL0 = 0.05, 1500 * math.pi / 30, 2000.0


@pytest.mark.parametrize("fixed", ["carrier", "ring"])
def test_stiff_meshes_follow_the_rigid_drivetrain_through_the_ramp(tmp_path, fixed):
    """Stiff linear meshes (5e6 N/mm: the lowest mode ~3 kHz against a 50 ms ramp), no losses. The input speed
    STEP-ramps to 1500 rpm (its acceleration 6 w0 s (1 - s)/T_r), the load to 2000 N m over the same 50 ms.
    Rigid Newton-Euler, transverse line-of-action forces F_b (reported F_t = F_b cos alpha_t):
    gear: F_b2 r_b2 = J_g a_g + T_L; the output body of the planetary: carrier held, the ring's shaft
    N F_pr r_br = (J_r + J_pinion) a_r + F_b2 r_b1 and each planet J_p a_p = (F_sp - F_pr) r_bp; ring held, the
    carrier N a cos(alpha) (F_sp + F_pr) = J_C a_c + F_b2 r_b1 (J_C with N m_p a^2) and each planet, spinning at
    (z_s/z_p)(w_s - w_c) - w_c against the sun in the housing's frame, J_p [(z_s/z_p)(a_s - a_c) - a_c] =
    (F_sp - F_pr) r_bp; the input torque J_s a_s + N F_sp r_bs. Agreement to 2e-4 (the meshes' quasi-static
    deflection lags the ramp by ~1/w_n; seen ~7e-5 at 10 ms, 1e-5 elsewhere), and 1e-8 once settled."""
    a = run_csv(tmp_path, linear_scene(fixed, "sun", k1=5e6, k2=5e6, ramp=TR))
    t = a["time_s"]
    s = np.clip(t / TR, 0, 1)
    a_s = W0 * 6 * s * (1 - s) / TR
    t_l = _step(t, TR, TL0)
    u = 82 / 22
    if fixed == "carrier":
        a_out = a_s * 22 / 82  # the ring's shaft, its running sense
        f_b2 = (J_GEAR2 * a_out * 19 / 57 + t_l) / RB_2
        f_pr = ((J_RING + J_PINION2) * a_out + f_b2 * RB_1) / (N_PL * RB_R)
        f_sp = f_pr + J_PLANET * a_s * 22 / 30 / RB_P
    else:
        a_c = a_s / (1 + u)
        f_b2 = (J_GEAR2 * a_c * 19 / 57 + t_l) / RB_2
        j_c = J_CARRIER + N_PL * M_PLANET * A_C**2 + J_PINION2
        total = (j_c * a_c + f_b2 * RB_1) / (N_PL * A_C * math.cos(ALPHA))  # F_sp + F_pr
        diff = J_PLANET * (22 / 30 * (a_s - a_c) - a_c) / RB_P  # F_sp - F_pr
        f_sp, f_pr = (total + diff) / 2, (total - diff) / 2
    t_in = J_SUN * a_s + N_PL * f_sp * RB_S
    hand = {"stage2_tangential_N": f_b2 * math.cos(ALPHA_T2), "input_torque_Nm": t_in}
    for j in range(1, N_PL + 1):
        hand[f"stage1_planet{j}_sun_tangential_N"] = f_sp * math.cos(ALPHA)
        hand[f"stage1_planet{j}_ring_tangential_N"] = f_pr * math.cos(ALPHA)
    ramp = (t >= 0.01) & (t <= TR)
    settled = t >= 0.08
    for name, want in hand.items():
        assert_allclose(a[name][ramp], want[ramp], rtol=2e-4, err_msg=name)
        assert_allclose(a[name][settled], want[settled], rtol=1e-8, err_msg=name)


@pytest.mark.parametrize("load", [T_OUT, -T_OUT])
@pytest.mark.parametrize(("fixed", "driven"), ARRANGEMENTS)
def test_settled_mean_forces_of_every_arrangement_with_losses_equal_the_design(tmp_path, fixed, driven, load):
    """eta 0.97 on the planetary, 0.98 on the helical stage, the default (calibrated ISO) law, the load forward and
    reversed: the settled window's mean of every planet mesh's force equals the design's static force in magnitude,
    signed by the flank the sun loads, i.e. as the sun's external torque `moment_balance_Nm.sun` (docs/output.md:
    negative with the carrier driven and the ring or the sun held, positive for a ring-driven star, all reversed
    by a reversed load); the input torque equals the design's; the planets share equally (K_gamma 1). The helical
    mesh: the design's force, over eta where the load reverses (the gear drives, docs/output.md). To 1e-5: the
    0.3 s run's window keeps a decaying start transient (~1e-7 seen on the speed increaser)."""
    text = STAR.replace('input = "sun"', f'input = "{driven}"').replace('fixed = "carrier"', f'fixed = "{fixed}"')
    text = text.replace(f"speed_rpm = {N_IN}\n", f"speed_rpm = {N_IN}\nramp_s = 0.05\n")
    text = text.replace(f"torque_Nm = {T_OUT}\n", f"torque_Nm = {load}\nramp_s = 0.05\n")
    text += "[simulation]\nduration_s = 0.3\nsteps = 300\n"
    doc = design(tmp_path, text)
    sim = run_json(tmp_path, "simulate", text)
    st, ss = doc["stages"], sim["summary"]["stages"]
    f_sp, f_pr = (abs(m["static_force_N"]["tangential"]) for m in st[0]["meshes"])
    flank = math.copysign(1.0, st[0]["moment_balance_Nm"]["sun"])
    for p in ss[0]["planets"]:
        assert_allclose(p["sun"]["tangential_N"]["mean"], flank * f_sp, rtol=1e-5)
        assert_allclose(p["ring"]["tangential_N"]["mean"], flank * f_pr, rtol=1e-5)
    assert_allclose(ss[0]["load_sharing_factor"], 1.0, rtol=1e-7)
    helical = st[1]["static_force_N"]["tangential"] / (ETA2 if load < 0 else 1.0)
    assert_allclose(ss[1]["tangential_N"]["mean"], helical, rtol=1e-5)
    assert_allclose(sim["summary"]["input_torque_Nm"], doc["input_torque_Nm"], rtol=1e-5)
    assert_allclose(sim["summary"]["ratio"], doc["total_ratio"], rtol=1e-7)


# ----------------------------------------------------------------------------------------------------- energy
@pytest.mark.parametrize("fixed", ["carrier", "ring"])
def test_energy_record_against_the_channels(tmp_path, fixed):
    """From rest, input and load ramped over 0.1 s, 0.4 s run, eta 0.97/0.98 (the losses are dissipation):
    input work = trapz(T_in w_in), load work = trapz(T_L w_out) (4000 samples, smooth ramps: 1e-5);
    kinetic change = the settled end's 1/2 sum J w^2 (planets at their kinematic spin: relative to the carrier when
    it is held, absolute (z_s/z_p)(w_s - w_c) - w_c on a moving carrier; the carrier's N m_p a^2 w_c^2);
    strain energy = sum F_n^2 / 2k (F_n = F_t / (cos alpha_t cos beta_b)); the record's damping loss closes it."""
    text = linear_scene(fixed, "sun", eta=0.97, eta2=0.98)
    text = text.replace(f"speed_rpm = {N_IN}\n", f"speed_rpm = {N_IN}\nramp_s = 0.1\n")
    text = text.replace(f"torque_Nm = {T_OUT}\n", f"torque_Nm = {T_OUT}\nramp_s = 0.1\n")
    text = text.replace("duration_s = 0.1\nsteps = 1000", "duration_s = 0.4\nsteps = 4000")
    a = run_csv(tmp_path, text)
    energy = run_json(tmp_path, "simulate", text)["energy"]
    t = a["time_s"]
    w1, w2, w3 = (a[f"shaft{i}_speed_rpm"] * math.pi / 30 for i in (1, 2, 3))
    assert_allclose(energy["input_work_J"], np.trapezoid(a["input_torque_Nm"] * w1, t), rtol=1e-5)
    assert_allclose(energy["load_work_J"], np.trapezoid(_step(t, 0.1, TL0) * w3, t), rtol=1e-5)
    if fixed == "carrier":  # shaft 2: the ring with the helical pinion
        w_planet = w1[-1] * 22 / 30
        kinetic = J_SUN * w1[-1] ** 2 + N_PL * J_PLANET * w_planet**2 + (J_RING + J_PINION2) * w2[-1] ** 2
    else:  # shaft 2: the carrier with the planets' mass and the helical pinion
        w_planet = 22 / 30 * (w1[-1] - w2[-1]) - w2[-1]
        j_c = J_CARRIER + N_PL * M_PLANET * A_C**2 + J_PINION2
        kinetic = J_SUN * w1[-1] ** 2 + N_PL * J_PLANET * w_planet**2 + j_c * w2[-1] ** 2
    kinetic = 0.5 * (kinetic + J_GEAR2 * w3[-1] ** 2)
    assert_allclose(energy["kinetic_change_J"], kinetic, rtol=1e-6)
    strain = sum(a[f"stage1_planet{j}_{m}_tangential_N"][-1] ** 2 for j in range(1, N_PL + 1)
                 for m in ("sun", "ring")) / math.cos(ALPHA) ** 2 / (2 * K1 * 1e3)
    strain += (a["stage2_tangential_N"][-1] / (math.cos(ALPHA_T2) * math.cos(BETA_B2))) ** 2 / (2 * K2 * 1e3)
    assert_allclose(energy["potential_change_J"], strain, rtol=1e-6)
    closed = energy["input_work_J"] - energy["load_work_J"] - energy["kinetic_change_J"] - energy["potential_change_J"]
    assert_allclose(energy["damping_loss_J"], closed, rtol=1e-8)
    # the losses are most of the dissipation: at least the settled power's 1 - 0.97 x 0.98 share of the input work
    # after the ramp, at most that share of all of it plus the transients' few per cent
    share = 1 - 0.97 * 0.98
    after = t >= 0.1
    assert share * np.trapezoid((a["input_torque_Nm"] * w1)[after], t[after]) < energy["damping_loss_J"]
    assert energy["damping_loss_J"] < 1.05 * share * energy["input_work_J"]


# ------------------------------------------------------------------------------------------ declared angles
def _two_planets(tmp_path, angles: str):
    """Scene S with two planets at ``angles``, carrier held, 300 rpm, time-varying contact lines on the planet
    meshes (the helical stage's constant: its own mesh frequency would break the symmetry below), no losses;
    30 sun-mesh periods, 400 samples each, the last 10 kept."""
    period = 60 / (22 * 300)  # the sun and ring mesh period, s (carrier held: z_s n_s = z_r n_r)
    text = star(count=2, planet=f", angles_deg = {angles}", eta=1.0,
                contact="[contact]\ntime_varying = true\n",
                extra=f"[simulation]\nduration_s = {30 * period!r}\nsteps = {30 * 400}\n").replace(
        f"efficiency = {ETA2}", "efficiency = 1.0").replace(f"speed_rpm = {N_IN}", "speed_rpm = 300")
    text = text.replace("gear   = {", "mesh = { time_varying = false }\ngear   = {", 1)
    a = run_csv(tmp_path, text)
    keep = a["time_s"] >= 20 * period - 1e-12
    return {m: (a[f"stage1_planet1_{m}_tangential_N"][keep], a[f"stage1_planet2_{m}_tangential_N"][keep])
            for m in ("sun", "ring")}


def _rms(x: np.ndarray) -> float:
    return float(np.sqrt(np.mean(x**2)))


def test_declared_planet_angles_phase_the_planet_meshes(tmp_path):
    """Two planets, 22/30/82 (one step 360/104°): at 0° and 180° (52 steps) planet 2's sun mesh leads planet 1's
    by z_s x 180/360 = 11 cycles and its ring mesh by -82/2 = -41: in phase, the two planets' forces are the same
    series. Declared at 0° and 90° (26 steps; unequal spacing, 90° and 270° gaps): 22/4 = 5.5 and -82/4 = -20.5
    cycles, half a mesh cycle on both meshes, so the torsional model is symmetric under half a mesh period: planet
    2's forces are planet 1's half a period later (200 samples). Were the declared angles ignored (equal spacing,
    180°), the two series would be equal. Tolerance: the sun mesh's stiffness steps fall on sample instants, where
    a series is not periodic to the sample either (its own one-period rms difference bounds the shift's)."""
    in_phase = _two_planets(tmp_path, "[0, 180]")
    for f1, f2 in in_phase.values():
        assert _rms(f1 - f2) <= 1e-9 * np.ptp(f1)
    half = _two_planets(tmp_path, "[0, 90]")
    n, h = 400, 200
    for f1, f2 in half.values():
        assert _rms(f1 - f2) > 0.1 * np.ptp(f1)  # the planets are out of phase
        periodic = _rms(f1[n:] - f1[:-n])
        shifted = _rms(f2[:-n] - f1[h:len(f1) - n + h])
        assert shifted <= 1.5 * periodic + 1e-4 * np.ptp(f1)


# ------------------------------------------------------------------------ parallel, planetary, star in a row
MIXED = """
title = "helical, then planetary (ring held), then star with unequally spaced planets"
[materials.steel]
density_kg_m3 = 7850
youngs_modulus_MPa = 206000
poisson_ratio = 0.3

[[stage]]
normal_module_mm = 3
helix_angle_deg = 15
efficiency = 0.985
pinion = { teeth = 20, face_width_mm = 40, hand = "left", material = "steel" }
gear   = { teeth = 50, face_width_mm = 40, hand = "right", material = "steel" }

[[stage]]
type = "planetary"
normal_module_mm = 4
efficiency = 0.98
sun    = { teeth = 24, face_width_mm = 40, material = "steel" }
planet = { teeth = 36, face_width_mm = 40, count = 3, material = "steel" }
ring   = { teeth = 96, face_width_mm = 40, material = "steel" }
fixed = "ring"
input = "sun"

[[stage]]
type = "planetary"
normal_module_mm = 6
efficiency = 0.975
sun    = { teeth = 21, face_width_mm = 60, material = "steel" }
planet = { teeth = 27, face_width_mm = 60, count = 4, material = "steel", angles_deg = [0, 93.75, 180, 273.75] }
ring   = { teeth = 75, face_width_mm = 60, material = "steel" }
fixed = "carrier"
input = "sun"

[input]
speed_rpm = 1500
ramp_s = 0.05

[load]
torque_Nm = 5000
ramp_s = 0.05

[simulation]
duration_s = 0.4
steps = 400
"""


def test_parallel_then_planetary_then_star_by_hand_and_settled(tmp_path):
    """Helical 20/50 (eta 0.985) drives the sun of a ring-held 24/36/96 x3 (eta 0.98), whose carrier drives the
    sun of a star 21/27/75 x4 (eta 0.975 = eta_0, planets at 0, 25, 48, 73 steps of 360/96 = 3.75°: (21 + 75)/4 = 24
    would allow equal spacing, these are not). Ratio 2.5 x 5 x 75/21; torques up the train with each stage's eta;
    F_t per planet T_s/(N r_s) on each planetary's sun mesh (the sun drives in both), eta_m F_t on the ring mesh;
    the helical mesh F_t = T_1 / r_1. The settled run's means equal them, and the planets share equally."""
    doc = design(tmp_path, MIXED)
    st = doc["stages"]
    ratio = 2.5 * 5 * 75 / 21
    assert_allclose(doc["total_ratio"], ratio, rtol=1e-12)
    assert_allclose(doc["output_speed_rpm"], 1500 / ratio, rtol=1e-12)
    assert_allclose([st[1]["sun"]["speed_rpm"], st[1]["carrier"]["speed_rpm"], st[2]["sun"]["speed_rpm"],
                     st[2]["ring"]["speed_rpm"]], [600, 120, 120, -120 * 21 / 75], rtol=1e-12)
    t_s3 = 5000 / (75 / 21 * 0.975)
    t_s2 = t_s3 / (5 * 0.98)
    t_1 = t_s2 / (2.5 * 0.985)
    assert_allclose(doc["input_torque_Nm"], t_1, rtol=1e-12)
    r_1 = 20 * 3 / math.cos(math.radians(15)) / 2e3
    f_sp2, f_sp3 = t_s2 / (3 * 0.048), t_s3 / (4 * 0.063)
    eta_m2 = math.sqrt((0.98 * 5 - 1) / 4)  # eta_0 = (eta (1 + u) - 1)/u, u = 4
    eta_m3 = math.sqrt(0.975)
    hand = [t_1 / r_1, f_sp2, eta_m2 * f_sp2, f_sp3, eta_m3 * f_sp3]
    got = [st[0]["static_force_N"]["tangential"], *(m["static_force_N"]["tangential"] for s in st[1:]
                                                   for m in s["meshes"])]
    assert_allclose(got, hand, rtol=1e-10)
    assert_allclose(st[2]["planet_angles_deg"], [0, 25 * 3.75, 48 * 3.75, 73 * 3.75], rtol=1e-12)
    assert st[2]["equal_spacing"] is False
    sim = run_json(tmp_path, "simulate", MIXED)["summary"]
    ss = sim["stages"]
    # the run is at rtol 1e-6: its global error is a small multiple of that (the engine `auto` takes depends on
    # whether the process has the compiled kernel loaded already; measured up to 6e-6 off on one of them)
    tol = 20 * 1e-6
    assert_allclose(ss[0]["tangential_N"]["mean"], hand[0], rtol=tol)
    for s, (f_sp, f_pr) in zip(ss[1:], ((hand[1], hand[2]), (hand[3], hand[4])), strict=True):
        assert_allclose([p["sun"]["tangential_N"]["mean"] for p in s["planets"]], f_sp, rtol=tol)
        assert_allclose([p["ring"]["tangential_N"]["mean"] for p in s["planets"]], f_pr, rtol=tol)
        assert_allclose(s["load_sharing_factor"], 1.0, rtol=1e-8)
    assert_allclose(sim["input_torque_Nm"], t_1, rtol=tol)
