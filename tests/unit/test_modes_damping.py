"""One damping model (issue 30 item 2): ``modes`` linearises what ``simulate`` integrates — the mesh damping law,
the couplings, a motor's slip damping dT/dw at its operating point and the load law's dT/dw.

References: the motor's slope by a central finite difference of its curve at the operating speed found by the
simulation layer's own root finder; the modal damping of a motor-driven chain from mass, stiffness and damping
matrices assembled by hand in the test; the decay of a free vibration in a simulated run, fitted by the ringing fit
of ``simulate`` and independently by scipy's curve_fit.
"""

from __future__ import annotations

import copy
import math
import tomllib
from pathlib import Path

import numpy as np
import pytest
from numpy.testing import assert_allclose
from scipy.optimize import curve_fit

from gearcli import api
from gearcli.config.schema import DesignFile
from gearcli.design import compute_design
from gearcli.io.channels import named
from gearcli.model.assembly import Layout
from gearcli.model.damping import body_damping, operating_speed_rad_s
from gearcli.model.elements import machine
from gearcli.simulate import ringing
from gearcli.simulate.motor import operating_point

ROOT = Path(__file__).resolve().parents[2]
CONFIGS = sorted((ROOT / "configs").glob("*.toml"))
MOTOR = {"rated_power_kW": 55.0, "rated_speed_rpm": 1480.0, "synchronous_speed_rpm": 1500.0,
         "breakdown_torque_ratio": 2.8, "locked_rotor_torque_ratio": 2.3}
# a 55 kW motor (2 kg m^2) on a coupling, one helical stage, a 20 kg m^2 drum on a coupling; the default mesh law
SCENE = {
    "stage": [{"normal_module_mm": 4.0, "helix_angle_deg": 12.0,
               "pinion": {"teeth": 19, "face_width_mm": 75.0, "hand": "left", "inertia_kg_m2": 0.05},
               "gear": {"teeth": 74, "face_width_mm": 70.0, "hand": "right", "inertia_kg_m2": 0.5}}],
    "input": {"speed_rpm": 1480.0, "drive": "motor", "motor": MOTOR, "starting": "direct", "inertia_kg_m2": 2.0,
              "coupling_stiffness_Nm_rad": 1.0e5, "coupling_damping_Nms_rad": 2.0},
    "load": {"torque_Nm": 1200.0, "inertia_kg_m2": 20.0, "coupling_stiffness_Nm_rad": 1.0e6,
             "coupling_damping_Nms_rad": 5.0},
}


def _case(doc: dict):
    cfg = DesignFile.model_validate(doc)
    design = compute_design(cfg)
    return cfg, design, Layout.of(api.model_spec(cfg, design))


def test_motor_slip_damping_is_the_slope_of_its_curve():
    _, _, lay = _case(copy.deepcopy(SCENE))
    w = operating_point(lay).stable_rad_s  # the simulation layer's root of T_m(w) = reflected load
    assert_allclose(operating_speed_rad_s(lay), w, rtol=1e-9)
    h = 1e-6 * w
    slope = (machine.motor_torque(lay.motor_row, 1e12, w + h)[0] - machine.motor_torque(lay.motor_row, 1e12, w - h)[0]) \
        / (2 * h)
    assert slope < 0  # the stable branch: torque falls with speed
    assert_allclose(body_damping(lay)[0], -slope, rtol=1e-7)  # O(h^2) of the finite difference


def test_load_law_damping_is_its_slope():
    doc = copy.deepcopy(SCENE)
    doc["load"]["speed_exponent"] = 2  # T_L = T_ref (w / w_n)^2: dT/dw = 2 T_ref w / w_n^2 at the load's speed
    _, _, lay = _case(doc)
    w_n = 1480.0 * 2 * math.pi / 60 * 19 / 74  # nominal drum speed
    w = operating_speed_rad_s(lay) * 19 / 74
    assert_allclose(body_damping(lay)[-1], 2 * 1200.0 * w / w_n**2, rtol=1e-12)


def _hand_matrices(cfg, design, lay):
    """M, K, C over (motor, shaft 1, shaft 2, drum), free, assembled here from the scene's numbers."""
    st = design.stages[0]
    r_bp, r_bg = st.pinion.base_diameter_mm / 2000, st.gear.base_diameter_mm / 2000
    cos2_bb = math.cos(math.radians(st.base_helix_angle_deg)) ** 2
    k_t = st.iso6336_mesh_stiffness_N_mm_um * st.face_width_mm * 1e6  # the ISO tangent, transverse, N/m
    J = np.array([2.0, 0.05, 0.5, 20.0])
    m_e = 1.0 / (r_bp**2 / J[1] + r_bg**2 / J[2])
    c_mesh = 2 * 0.05 * math.sqrt(k_t / cos2_bb * m_e)  # zeta 0.05 on k_lin = k_n (DESIGN section 6)
    K, C = np.zeros((4, 4)), np.zeros((4, 4))
    for (a, b, ra, rb), k, c in (((0, 1, 1.0, 1.0), 1.0e5, 2.0), ((1, 2, r_bp, r_bg), k_t, c_mesh),
                                 ((2, 3, 1.0, 1.0), 1.0e6, 5.0)):
        lev = np.zeros(4)
        lev[a], lev[b] = ra, -rb
        K += k * np.outer(lev, lev)
        C += c * np.outer(lev, lev)
    w = operating_point(lay).stable_rad_s
    h = 1e-5 * w
    C[0, 0] -= (machine.motor_torque(lay.motor_row, 1e12, w + h)[0]
                - machine.motor_torque(lay.motor_row, 1e12, w - h)[0]) / (2 * h)
    return J, K, C


def test_modal_damping_of_a_motor_driven_chain_by_hand():
    cfg, design, lay = _case(copy.deepcopy(SCENE))
    J, K, C = _hand_matrices(cfg, design, lay)
    A = np.block([[np.zeros((4, 4)), np.eye(4)], [-K / J[:, None], -C / J[:, None]]])
    lam = sorted((z for z in np.linalg.eigvals(A) if z.imag > 0), key=abs)
    free = {a.boundary: a for a in api.modes(cfg, design)}["free"]
    elastic = [m for m in free.modes if not m.rigid]
    assert len(elastic) == len(lam) == 3
    for m, z in zip(elastic, lam, strict=True):
        assert_allclose(m.damping_ratio, -z.real / abs(z), rtol=1e-5, err_msg=f"mode {m.number}")  # O(h^2) of FD
    # the motor's slip damping dominates the lowest mode: without it the drum would ring at ~0.1 %
    assert elastic[0].damping_ratio > 0.03
    C[0, 0] = 0.0
    A = np.block([[np.zeros((4, 4)), np.eye(4)], [-K / J[:, None], -C / J[:, None]]])
    z0 = min((z for z in np.linalg.eigvals(A) if z.imag > 0), key=abs)
    assert -z0.real / abs(z0) < 0.1 * elastic[0].damping_ratio


@pytest.fixture(scope="module")
def ringing_run():
    """The DOL start ends at ~0.88 s; the window 1.0 .. 1.07 s holds the lowest mode's free decay (its decay time
    ~75 ms outlasts the window: the ringing fit's case)."""
    doc = {**copy.deepcopy(SCENE), "simulation": {"duration_s": 1.07, "steps": 2140, "window_start_s": 1.0}}
    cfg, design, _ = _case(doc)
    return cfg, design, api.simulate(cfg, design, want_series=True)


def test_lowest_mode_damping_equals_the_ringing_fit(ringing_run):
    cfg, design, result = ringing_run
    lowest = next(m for m in {a.boundary: a for a in api.modes(cfg, design)}["free"].modes if not m.rigid)
    rings = [d for d in result.diagnostics if d.code == "window_ringing"]
    assert rings, result.warnings
    r = min(rings, key=lambda d: abs(d.data["mode_frequency_Hz"] - lowest.frequency_Hz))
    assert_allclose(r.data["mode_frequency_Hz"], lowest.frequency_Hz, rtol=0.03)  # damped vs undamped, nonlinear mesh
    # within the fit's stated resolution (half a step of its trial decay rates, 5.9 %)
    assert r.data["damping_ratio_uncertainty"] == ringing.SIGMA_UNCERTAINTY
    assert abs(r.data["damping_ratio"] / lowest.damping_ratio - 1) <= ringing.SIGMA_UNCERTAINTY


def test_lowest_mode_damping_equals_an_independent_fit_of_the_decay(ringing_run):
    cfg, design, result = ringing_run
    lowest = next(m for m in {a.boundary: a for a in api.modes(cfg, design)}["free"].modes if not m.rigid)
    t = result.time_s
    x = named(result)["load_coupling_torque_Nm"]
    m = t >= 1.0
    tau, y = t[m] - 1.0, x[m]

    def decay(tau, c, a, b, sigma, omega):
        return c + np.exp(-sigma * tau) * (a * np.cos(omega * tau) + b * np.sin(omega * tau))

    w0 = 2 * math.pi * lowest.frequency_Hz
    p, cov = curve_fit(decay, tau, y, p0=[y.mean(), y[0] - y.mean(), 0.0, lowest.damping_ratio * w0, w0])
    zeta = p[3] / math.hypot(p[3], p[4])
    # 2 %: the linearisation's own error (the e = 1.5 mesh and the motor curve at the vibration's amplitude) is far
    # above the fit's statistical one (1e-3 relative)
    assert_allclose(zeta, lowest.damping_ratio, rtol=0.02)


def _default_law_doc(path: Path) -> dict:
    """A config with the default mesh law and no other dampers (couplings, shafts): the damping the law gives."""
    doc = tomllib.loads(path.read_text())
    doc.pop("contact", None)
    for st in doc["stage"]:
        st.pop("mesh", None)
        if "shaft" in st:
            st["shaft"]["damping_Nms_rad"] = 0.0
    for table in ("input", "load"):
        if "coupling_damping_Nms_rad" in doc[table]:
            doc[table]["coupling_damping_Nms_rad"] = 0.0
    return doc


@pytest.mark.parametrize("path", CONFIGS, ids=lambda p: p.stem)
def test_default_law_damps_mesh_dominated_modes_between_1_and_20_percent(path):
    """Acceptance: modes a single mesh dominates (half its strain energy or more), at the boundary the run
    integrates, have modal damping ratios between 1 % and 20 % under the default law (0.05 per mesh)."""
    cfg = DesignFile.model_validate(_default_law_doc(path))
    design = compute_design(cfg)
    boundary = "clamped_input" if cfg.input.drive == "speed" else "free"
    ana = {a.boundary: a for a in api.modes(cfg, design)}[boundary]
    for m in ana.modes:
        if m.rigid or "mesh" not in m.dominant or max(m.energy_share) < 0.5:
            continue  # a planetary stage's modes share their strain energy among its planet meshes
        assert 0.01 <= m.damping_ratio <= 0.20, f"mode {m.number} {m.frequency_Hz:.4g} Hz ({m.dominant})"


def test_an_overhauling_load_linearises_at_the_generating_crossing():
    """A lowering load (-600 N m at the drum, -600/3.895 = -154 N m at the motor, inside the generating breakdown
    -2.8 T_r): the motor brakes it above its synchronous speed; modes' operating speed is that crossing (the
    simulation layer's root), not the nominal speed it fell back to when the scan stopped at synchronous speed."""
    doc = copy.deepcopy(SCENE)
    doc["load"]["torque_Nm"] = -600.0
    _, _, lay = _case(doc)
    w = operating_point(lay).stable_rad_s
    assert w is not None and w > 1500 * math.pi / 30  # generating: above the synchronous speed
    net = machine.motor_torque(lay.motor_row, 1e12, w)[0] + 600.0 * 19 / 74  # lossless stage: T_L rho
    assert abs(net) < 1e-6
    assert_allclose(operating_speed_rad_s(lay), w, rtol=1e-9)


def test_a_motor_driven_planetary_is_linearised_at_the_simulated_operating_speed():
    """configs/mixer_planetary_motor.toml: the settled run's motor speed against its steady net torque, written out
    here (the load at the drum through the train's power efficiency: its planetary stage's eta as a whole, not
    each planet mesh's eta_m; DESIGN section 13: modes linearise what simulate integrates). The linearisation used
    the product of every lossy connector's eta (a planetary's six planet meshes: eta_m^6), a reflected load 5 % high
    and an operating speed 0.12 rad/s low."""
    from scipy.optimize import brentq

    loaded = api.load(str(ROOT / "configs" / "mixer_planetary_motor.toml"), [])
    design = api.design(loaded)
    lay = Layout.of(api.model_spec(loaded.design, design))
    rho = lay.bodies[-1].ratio
    eta = math.prod(s.efficiency for s in design.stages)  # the stages' power efficiencies, input to drum

    def net(w: float) -> float:
        g = machine.load_factor(lay.load_law, w * rho)[0] if lay.load_law else 1.0
        return machine.motor_torque(lay.motor_row, 1e12, w)[0] - loaded.design.load.torque_Nm * g * rho / eta

    ws = lay.motor_row[machine.M_WS]
    w_hand = brentq(net, 0.9 * ws, ws, xtol=1e-13 * ws)
    assert_allclose(operating_speed_rad_s(lay), w_hand, rtol=1e-9)
    assert_allclose(operating_point(lay).stable_rad_s, w_hand, rtol=1e-9)
