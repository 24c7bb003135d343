"""Drivetrain elements (motor, couplings, flexible shafts, drum) against closed forms written out here.

Mass and stiffness matrices are assembled by hand in each test from the inertias, base radii and
stiffnesses, independently of gearcli.model.assembly; frequencies are compared to 1e-9 where the
model is exactly the hand model, looser where a limit is taken (stated beside each bound).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import scipy.linalg
from numpy.testing import assert_allclose

from gearcli.model import CoupledInertia, DriveSpec, FlexibleShaft, Layout, LoadSpec, MeshSpec, ModelSpec, SpringSpec
from gearcli.model.modes import modal_analysis

ROOT = Path(__file__).resolve().parents[2]
BETA_B = math.radians(10.0)


def linear_mesh(rp: float, rg: float, k_line: float) -> MeshSpec:
    """A linear (e = 1) mesh whose stiffness along the transverse line of action is ``k_line``."""
    return MeshSpec(base_radius_pinion_m=rp, base_radius_gear_m=rg, base_helix_angle_rad=BETA_B,
                    transverse_pressure_angle_rad=math.radians(20.4), helix_angle_rad=math.radians(10.6),
                    stiffness_N_m_e=k_line / math.cos(BETA_B) ** 2, exponent=1.0, damping_Ns_m=0.0,
                    full_damping_m=1e-4)


def freqs_by_hand(K: np.ndarray, M: np.ndarray) -> np.ndarray:
    w2 = scipy.linalg.eigh(K, M, eigvals_only=True)
    return np.sqrt(np.clip(w2, 0.0, None)) / (2 * math.pi)


def test_two_inertia_coupling_frequency():
    # motor J1 on a coupling k to the input pinion; the mesh 1e6 x stiffer than the coupling ties the
    # pinion and gear into one reduced inertia J2 = J_p + J_g (r_p/r_g)^2. Free chain: the coupling mode
    # is sqrt(k (J1 + J2) / (J1 J2)) / 2 pi; the stiff mesh moves it by ~k/k_mesh ~ 1e-6 relative.
    J1, Jp, Jg, k = 0.25, 0.6, 20.0, 3.0e4
    rp, rg = 0.06, 0.15
    spec = ModelSpec((linear_mesh(rp, rg, 1e6 * k / rg**2),), (Jp, Jg), DriveSpec("torque", 10.0, 0.0, 100.0),
                     LoadSpec(100.0 * rg / rp), motor=CoupledInertia(J1, SpringSpec(k)))
    J2 = Jp + Jg * (rp / rg) ** 2
    expected = math.sqrt(k * (J1 + J2) / (J1 * J2)) / (2 * math.pi)
    free = modal_analysis(Layout.of(spec), "free")
    assert_allclose(free.modes[1].frequency_Hz, expected, rtol=1e-5)  # the stiff-mesh limit: ~1e-6
    assert free.modes[1].dominant == "input coupling"


def test_free_chain_has_a_rigid_mode_at_zero_moving_with_the_speed_ratios():
    spec = ModelSpec((linear_mesh(0.06, 0.15, 2e8),), (0.6, 20.0), DriveSpec("torque", 10.0, 0.0, 100.0),
                     LoadSpec(250.0), motor=CoupledInertia(0.25, SpringSpec(3e4)),
                     drum=CoupledInertia(500.0, SpringSpec(1e6)))
    free = modal_analysis(Layout.of(spec), "free")
    rigid = free.modes[0]
    assert rigid.rigid and rigid.frequency_Hz == 0.0
    # body angles of a rigid rotation follow the speed ratios: 1, 1, r_p/r_g, r_p/r_g (normalised to the largest)
    assert_allclose(rigid.shape, [1.0, 1.0, 0.4, 0.4], rtol=1e-9)
    assert not any(m.rigid for m in free.modes[1:])
    clamped = modal_analysis(Layout.of(spec), "clamped_input")
    assert not any(m.rigid for m in clamped.modes) and len(clamped.modes) == 3


def two_stage_with_shaft(drive: str = "speed") -> tuple[ModelSpec, dict]:
    p = dict(Jp1=0.5, Jg1=8.0, Jp2=1.5, Jg2=60.0, r1p=0.06, r1g=0.15, r2p=0.08, r2g=0.22, k1=3e8, k2=6e8, ks=4e5)
    meshes = (linear_mesh(p["r1p"], p["r1g"], p["k1"]), linear_mesh(p["r2p"], p["r2g"], p["k2"]))
    spec = ModelSpec(meshes, (p["Jp1"], p["Jg1"] + p["Jp2"], p["Jg2"]), DriveSpec(drive, 60.0, 0.0, 200.0),
                     LoadSpec(500.0), shafts=(FlexibleShaft(SpringSpec(p["ks"]), p["Jg1"]),))
    return spec, p


def test_shaft_between_two_meshes_against_a_hand_assembled_eigenproblem():
    spec, p = two_stage_with_shaft()
    # clamped input (pinion 1 held): coordinates (theta_g1, theta_p2, theta_g2);
    # delta_1 = -r1g theta_g1, delta_s = theta_g1 - theta_p2, delta_2 = r2p theta_p2 - r2g theta_g2
    K = np.array([[p["k1"] * p["r1g"] ** 2 + p["ks"], -p["ks"], 0.0],
                  [-p["ks"], p["ks"] + p["k2"] * p["r2p"] ** 2, -p["k2"] * p["r2p"] * p["r2g"]],
                  [0.0, -p["k2"] * p["r2p"] * p["r2g"], p["k2"] * p["r2g"] ** 2]])
    M = np.diag([p["Jg1"], p["Jp2"], p["Jg2"]])
    ana = modal_analysis(Layout.of(spec), "clamped_input")
    assert_allclose([m.frequency_Hz for m in ana.modes], freqs_by_hand(K, M), rtol=1e-9)
    # free: add theta_p1 in front; delta_1 = r1p theta_p1 - r1g theta_g1
    Kf = np.zeros((4, 4))
    Kf[1:, 1:] = K
    Kf[0, 0] = p["k1"] * p["r1p"] ** 2
    Kf[0, 1] = Kf[1, 0] = -p["k1"] * p["r1p"] * p["r1g"]
    free = modal_analysis(Layout.of(spec), "free")
    hand = freqs_by_hand(Kf, np.diag([p["Jp1"], p["Jg1"], p["Jp2"], p["Jg2"]]))
    assert_allclose([m.frequency_Hz for m in free.modes[1:]], hand[1:], rtol=1e-9)
    assert abs(hand[0]) < 1e-6 * hand[-1] and free.modes[0].frequency_Hz == 0.0


def test_modal_strain_energy_shares_sum_to_one_and_name_the_soft_element():
    spec, _ = two_stage_with_shaft()
    for boundary in ("clamped_input", "free"):
        for m in modal_analysis(Layout.of(spec), boundary).modes:
            if not m.rigid:
                assert_allclose(sum(m.energy_share), 1.0, rtol=1e-12)
                assert min(m.energy_share) >= 0.0
    # the shaft (4e5 N m/rad) is far softer than the meshes: the first mode is the shaft's
    assert modal_analysis(Layout.of(spec)).modes[0].dominant == "shaft 2"


def test_rigid_limit_of_very_stiff_elements_gives_the_rigid_model_frequencies():
    # couplings and shaft 1e6 x stiffer than the meshes' rotational stiffness: clamped, the motor holds the
    # pinion through an almost rigid coupling, the drum adds its inertia to the last shaft
    spec, p = two_stage_with_shaft()
    stiff = 1e6 * p["k2"] * p["r2g"] ** 2
    J_drum = 40.0
    flexible = ModelSpec(spec.meshes, spec.inertias_kg_m2, spec.drive, spec.load,
                         motor=CoupledInertia(0.3, SpringSpec(stiff)), drum=CoupledInertia(J_drum, SpringSpec(stiff)),
                         shafts=(FlexibleShaft(SpringSpec(stiff), p["Jg1"]),))
    rigid = ModelSpec(spec.meshes, (p["Jp1"], p["Jg1"] + p["Jp2"], p["Jg2"] + J_drum), spec.drive, spec.load)
    f_flex = [m.frequency_Hz for m in modal_analysis(Layout.of(flexible)).modes]
    f_rigid = [m.frequency_Hz for m in modal_analysis(Layout.of(rigid)).modes]
    assert_allclose(f_flex[:len(f_rigid)], f_rigid, rtol=1e-5)  # stiffness ratio 1e-6: shifts ~1e-6
    assert min(f_flex[len(f_rigid):]) > 100 * max(f_rigid)  # the element modes went far above


def test_mean_mesh_forces_with_elements_equal_statics():
    # the seed with a motor, couplings, flexible shafts and a drum, all well damped; in steady state the
    # mean of every mesh force is the design's static force (lossless stages), whatever the elements
    from gearcli.config import load_design
    from gearcli.design import compute_design
    from gearcli.simulate import run_simulation

    sets = ["input.inertia_kg_m2=0.25", "input.coupling_stiffness_Nm_rad=3e4", "input.coupling_damping_Nms_rad=150",
            "stage.0.shaft.stiffness_Nm_rad=5e5", "stage.0.shaft.damping_Nms_rad=300",
            "stage.1.shaft.stiffness_Nm_rad=2e6", "stage.1.shaft.damping_Nms_rad=2000",
            "load.inertia_kg_m2=60", "load.coupling_stiffness_Nm_rad=1e6", "load.coupling_damping_Nms_rad=3e4",
            "simulation.duration_s=2.0", "simulation.steps=8000"]
    loaded = load_design(str(ROOT / "configs" / "concrete_mixer.toml"), sets)
    design = compute_design(loaded.design)
    sim = run_simulation(loaded.design, design, want_series=False)
    for st, dyn in zip(design.stages, sim.stages, strict=True):
        # the window mean differs from the static force by the momentum change of the residual vibration
        # (std ~10 % of the force, lightly damped mesh modes) over the 1.5 s window: measured 0.2-0.8 %
        assert_allclose(dyn.tangential_N.mean, st.static_force_N.tangential, rtol=1e-2)
    assert sim.solver.energy_residual < 1e-4  # the elements' energy is booked
    assert_allclose(sim.ratio, design.total_ratio, rtol=1e-3)  # the reducer's ratio, not motor over drum


@pytest.mark.parametrize("toml, key", [
    ("[stage.shaft]\nstiffness_Nm_rad = 1e5\n", "stage[2].shaft"),
])
def test_a_shaft_after_the_last_stage_is_refused_naming_the_key(tmp_path, toml, key):
    from gearcli.config import load_design
    from gearcli.errors import ConfigError

    text = (ROOT / "configs" / "concrete_mixer.toml").read_text()
    last = text.index("[contact]")
    path = tmp_path / "bad.toml"
    path.write_text(text[:last] + toml + "\n" + text[last:])
    with pytest.raises(ConfigError) as err:
        load_design(str(path), [])
    assert key in str(err.value) and err.value.exit_code == 2


def test_a_motor_without_its_coupling_is_refused():
    from gearcli.config import load_design
    from gearcli.errors import ConfigError

    with pytest.raises(ConfigError, match="coupling_stiffness_Nm_rad"):
        load_design(str(ROOT / "configs" / "concrete_mixer.toml"), ["input.inertia_kg_m2=0.25"])
