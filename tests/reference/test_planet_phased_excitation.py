"""A planetary stage's mesh orders against its modes: every planet mesh at its mesh phase, repeated modes as one
eigenspace (trial tr15c: a 21/30/81 stage with 3 planets was warned "strongly excited" where the 2x mesh order met
its repeated 3365 Hz planet modes, which in-phase meshing cannot drive; the simulation showed no resonance).

References, independent of the code: a hand-built torsional model of the stage (the mesh deflections the planetary
spec documents: sun mesh r_bp th_p + r_bs th_s - (r_bs + r_bp) th_c, ring mesh (ring held) -r_bp th_p - (r_br - r_bp)
th_c; the carrier carries the planets' masses at the centre distance), the planet-mode frequency in closed form
(sun and carrier at rest: omega^2 = 2 k r_bp^2 / J_p), and Parker & Lin's rule: with mesh phases h z_s psi_j / 2 pi
(sun) and -h z_r psi_j / 2 pi (ring), harmonic h drives the rotational modes only when h z_s / N is an integer and
the planet modes only when it is not."""

from __future__ import annotations

import math

import numpy as np
import pytest

from gearcli.config import load_design
from gearcli.design import compute_design
from gearcli.model import modes as modes_mod
from gearcli.model.assembly import Layout
from gearcli.model.planet_excitation import phased_participation
from gearcli.scene import spec_from_design

K_MESH = 5e8  # N/m: stiffness = 5e5 N/mm, exponent 1 (linear: its tangent at any load)
M, ALPHA, N = 3e-3, math.radians(20.0), 3
J_S, J_P, M_P, J_C, J_IN, J_DRUM = 0.002, 0.004, 1.6, 0.15, 0.05, 30.0
K_IN, K_OUT = 4e4, 1e5

SCENE = """title = "planetary {zs}/{zp}/{zr}"
[[stage]]
type = "planetary"
normal_module_mm = 3
normal_pressure_angle_deg = 20
sun    = {{ teeth = {zs}, face_width_mm = 40, inertia_kg_m2 = 0.002 }}
planet = {{ teeth = {zp}, face_width_mm = 38, count = 3, inertia_kg_m2 = 0.004, mass_kg = 1.6 }}
ring   = {{ teeth = {zr}, face_width_mm = 38 }}
carrier = {{ inertia_kg_m2 = 0.15 }}
fixed = "ring"
input = "sun"
[contact]
stiffness = 5e5
exponent = 1
damping_ratio = 0.05
[input]
speed_rpm = {rpm}
inertia_kg_m2 = 0.05
coupling_stiffness_Nm_rad = 4e4
coupling_damping_Nms_rad = 3
[load]
torque_Nm = 900
inertia_kg_m2 = 30
coupling_stiffness_Nm_rad = 1e5
coupling_damping_Nms_rad = 20
"""


def _layout(tmp_path, zs: int, zp: int, zr: int, rpm: float = 1450.0) -> Layout:
    path = tmp_path / f"pl_{zs}_{rpm}.toml"
    path.write_text(SCENE.format(zs=zs, zp=zp, zr=zr, rpm=rpm))
    cfg = load_design(str(path), []).design
    return Layout.of(spec_from_design(cfg, compute_design(cfg)))


def _hand(zs: int, zp: int, zr: int, gamma: float = 0.0):
    """The clamped-input chain by hand (free bodies: sun, planets 1-3, carrier, drum): frequencies (Hz), mass-
    normalised shapes, and each mesh's row of the deflection map with its phase in cycles at the mesh frequency."""
    r_bs, r_bp, r_br = (z * M / 2 * math.cos(ALPHA) for z in (zs, zp, zr))
    r_c = (zs + zp) * M / 2
    J = np.array([J_S, J_P, J_P, J_P, J_C + N * M_P * r_c**2, J_DRUM])
    rows, k, phase = [], [], []
    spring = np.zeros(6)
    spring[0] = 1.0  # the input coupling, motor held
    rows.append(spring), k.append(K_IN), phase.append(None)
    spring = np.zeros(6)
    spring[4], spring[5] = 1.0, -1.0
    rows.append(spring), k.append(K_OUT), phase.append(None)
    for j in range(N):
        psi = 2 * math.pi * j / N
        sun = np.zeros(6)
        sun[0], sun[1 + j], sun[4] = r_bs, r_bp, -(r_bs + r_bp)
        ring = np.zeros(6)
        ring[1 + j], ring[4] = -r_bp, -(r_br - r_bp)
        rows += [sun, ring]
        k += [K_MESH, K_MESH]
        phase += [zs * psi / (2 * math.pi), -zr * psi / (2 * math.pi) + gamma]
    R, k_arr = np.array(rows), np.array(k)
    inv = 1 / np.sqrt(J)
    w2, u = np.linalg.eigh(inv[:, None] * (R.T @ (k_arr[:, None] * R)) * inv[None, :])
    return np.sqrt(w2) / (2 * math.pi), inv[:, None] * u, R, k_arr, phase


def _hand_participation(zs, zp, zr, h: int, modes: list[int], gamma: float) -> float:
    """Sum over the modes (an orthonormal basis of one eigenspace) of |sum_c k_c (R phi)_c e^(2 pi i h p_c)|^2, over
    the planet meshes' summed stiffness times omega^2."""
    f, phi, R, k, phase = _hand(zs, zp, zr, gamma)
    meshes = [c for c, p in enumerate(phase) if p is not None]
    turn = np.array([np.exp(2j * math.pi * h * phase[c]) for c in meshes])
    total = 0.0
    for m in modes:
        P = np.sum(k[meshes] * (R[meshes] @ phi[:, m]) * turn)
        total += abs(P) ** 2 / (k[meshes].sum() * (2 * math.pi * f[m]) ** 2)
    return total


def _gamma(lay: Layout) -> float:
    """The ring mesh's contact-line phase against its planet's sun mesh (tooth geometry: an input here)."""
    return lay.spec.stage_models[0].ring_contact_phase_cycles  # type: ignore[union-attr]


def _crossing(lay: Layout, mode, order: int):
    """The order's crossing of the mode at any speed; the mode's own (report) and the Campbell diagram's agree."""
    (src,) = [o for o in modes_mod.excitation_sources(lay) if o.name == f"stage 1 mesh {order}x"]
    found = modes_mod.order_crossing(lay, "clamped_input", 1.0, mode, src)
    assert all(c == found for c in mode.crossings if c.excitation == src.name)
    assert all(c.crossing == found for c in modes_mod.campbell_data(lay, max_input_rpm=1e6).crossings
               if c.mode == mode.number and c.crossing.excitation == src.name)
    return found


def _mesh_rpm(f_hz: float, order: int, zs: int, zr: int) -> float:
    """Input (sun) speed at which mesh order ``order`` reaches ``f_hz``: f_mesh = z_s (n_s - n_c) / 60, n_c = n_s
    z_s / (z_s + z_r) with the ring held."""
    return 60.0 * f_hz / (order * zs * zr / (zs + zr))


def _elastic(ana):
    return [m for m in ana.modes if not m.rigid]


def test_in_phase_planets_leave_the_repeated_planet_modes_unexcited(tmp_path):
    zs, zp, zr = 21, 30, 81  # z_s / N = 7: the planets mesh in phase at every harmonic
    f_hand, *_ = _hand(zs, zp, zr)
    f_planet = math.sqrt(2 * K_MESH * (zp * M / 2 * math.cos(ALPHA)) ** 2 / J_P) / (2 * math.pi)
    assert sorted(f_hand)[3] == pytest.approx(f_planet, rel=1e-9) == sorted(f_hand)[4]
    rpm = _mesh_rpm(f_planet, 2, zs, zr)  # the 2x order right on the planet modes (tr15c's 6053.5 rpm)
    lay = _layout(tmp_path, zs, zp, zr, rpm)
    modes = _elastic(modes_mod.modal_analysis(lay))
    np.testing.assert_allclose([m.frequency_Hz for m in modes], np.sort(f_hand), rtol=1e-6)
    pair = [m for m in modes if abs(m.frequency_Hz - f_planet) < 1e-6 * f_planet]
    assert len(pair) == 2
    for m in pair:
        for h in (1, 2, 3):
            assert _crossing(lay, m, h).participation < 1e-12
    warned = modes_mod.resonances(lay)
    assert not [r for r in warned if r.mode in {m.number for m in pair} and r.source == "mesh"]
    # the highest (rotational) mode is driven: at 3x, as the hand model's phased sum says, and warned there
    top = modes[-1]
    want = _hand_participation(zs, zp, zr, 3, [5], _gamma(lay))
    assert want > 0.1
    assert _crossing(lay, top, 3).participation == pytest.approx(want, rel=1e-6)
    lay3 = _layout(tmp_path, zs, zp, zr, _mesh_rpm(top.frequency_Hz, 3, zs, zr))
    (hit,) = [r for r in modes_mod.resonances(lay3) if r.excitation == "stage 1 mesh 3x"]
    assert hit.mode == top.number and hit.participation == pytest.approx(want, rel=1e-6)
    assert hit.amplification == pytest.approx(want / (2 * hit.damping_ratio), rel=1e-12)


def test_sequentially_phased_planets_drive_the_planet_modes_at_the_harmonic_parker_names(tmp_path):
    zs, zp, zr = 20, 31, 82  # z_s / N = 20 / 3: sequential; h z_s mod 3 = 2, 1, 0 for h = 1, 2, 3
    f_hand, *_ = _hand(zs, zp, zr)
    order = np.argsort(f_hand)
    f_planet = math.sqrt(2 * K_MESH * (zp * M / 2 * math.cos(ALPHA)) ** 2 / J_P) / (2 * math.pi)
    planet = [int(i) for i in order if abs(f_hand[i] - f_planet) < 1e-9 * f_planet]
    rotational = [int(i) for i in order[2:] if int(i) not in planet]  # above the couplings' two modes
    assert len(planet) == 2 and len(rotational) == 2
    lay = _layout(tmp_path, zs, zp, zr, _mesh_rpm(f_planet, 1, zs, zr))
    modes = _elastic(modes_mod.modal_analysis(lay))
    pair = [m for m in modes if abs(m.frequency_Hz - f_planet) < 1e-6 * f_planet]
    rot = [m for m in modes[2:] if m not in pair]
    for h in (1, 2):  # sequential: the planet modes, not the rotational ones
        want = _hand_participation(zs, zp, zr, h, planet, _gamma(lay))
        assert want > 0.1
        for m in pair:
            assert _crossing(lay, m, h).participation == pytest.approx(want, rel=1e-6)
        for m in rot:
            assert _crossing(lay, m, h).participation < 1e-12
    for m in pair:  # h = 3: in phase, the rotational modes only
        assert _crossing(lay, m, 3).participation < 1e-12
    for m, i in zip(rot, rotational, strict=True):
        want = _hand_participation(zs, zp, zr, 3, [i], _gamma(lay))
        assert _crossing(lay, m, 3).participation == pytest.approx(want, rel=1e-6)
    # at the 1x crossing of the planet modes: one warning for the repeated pair, at its first mode
    warned = [r for r in modes_mod.resonances(lay) if r.source == "mesh"]
    assert [r.mode for r in warned if r.excitation == "stage 1 mesh 1x"] == [pair[0].number]
    assert "repeated" in warned[0].message


def test_a_repeated_mode_participation_does_not_depend_on_the_basis(tmp_path):
    zs, zp, zr = 20, 31, 82
    lay = _layout(tmp_path, zs, zp, zr)
    ana = modes_mod.modal_analysis(lay)
    und = modes_mod._undamped(lay, "clamped_input", 1.0)
    pair = [m.number - 1 for m in ana.modes if m.frequency_Hz > 0 and
            sum(abs(x.frequency_Hz - m.frequency_Hz) < 1e-6 * m.frequency_Hz for x in ana.modes) == 2]
    assert len(pair) == 2 and modes_mod.repeated_group(und, pair[0]) == tuple(pair)
    (src,) = [o for o in modes_mod.excitation_sources(lay) if o.name == "stage 1 mesh 1x"]
    u = np.asarray(und.u[:, und.order[pair]])
    base = phased_participation(und.k, und.R, und.inv_sqrt, u, src.phased)
    alone = [phased_participation(und.k, und.R, und.inv_sqrt, u[:, [i]], src.phased) for i in (0, 1)]
    assert sum(alone) == pytest.approx(base, rel=1e-9)
    for angle in (0.3, 1.1, 2.5):
        c, s = math.cos(angle), math.sin(angle)
        turned = u @ np.array([[c, -s], [s, c]])
        assert phased_participation(und.k, und.R, und.inv_sqrt, turned, src.phased) == pytest.approx(base, rel=1e-9)
        # each rotated vector alone gives another share: only the eigenspace's sum is a property of the chain
        one = phased_participation(und.k, und.R, und.inv_sqrt, turned[:, [0]], src.phased)
        assert 0.0 <= one <= base * (1 + 1e-9)
    assert not any(m.rigid for m in ana.modes)  # the hand model's modes, ascending, are the analysis's ranks
    assert base == pytest.approx(_hand_participation(zs, zp, zr, 1, pair, _gamma(lay)), rel=1e-6)


def test_orders_that_cyclic_symmetry_cancels_cross_with_participation_zero_not_round_off(tmp_path):
    """tr22b: a 21/29/79 star's rotational modes were listed as crossed by the 2x and 3x mesh orders "(2e-28 %,
    2.8e-29)": the four planets' phased sum, sum_j exp(2 pi i h z_s j / N), is exactly 0 for h z_s / N = 10.5 and
    15.75 (the hand sum below), and the docs promise 0 where the phases cancel. Here 20/31/82 with three planets:
    h z_s / N = 20/3 and 40/3 leave the rotational modes unexcited at h = 1, 2, exactly."""
    zs, zp, zr = 20, 31, 82
    for h in (1, 2):
        assert abs(sum(np.exp(2j * math.pi * h * zs * j / N) for j in range(N))) < 1e-12  # the cancellation
    f_hand, *_ = _hand(zs, zp, zr)
    f_planet = math.sqrt(2 * K_MESH * (zp * M / 2 * math.cos(ALPHA)) ** 2 / J_P) / (2 * math.pi)
    lay = _layout(tmp_path, zs, zp, zr, 3000.0)
    modes = _elastic(modes_mod.modal_analysis(lay))
    rotational = [m for m in modes[2:] if abs(m.frequency_Hz - f_planet) > 1e-6 * f_planet]
    assert len(rotational) == 2
    for m in rotational:
        for h in (1, 2):
            c = _crossing(lay, m, h)
            assert c.participation == 0.0 and c.amplification == 0.0
        assert _crossing(lay, m, 3).participation > 0.1  # h z_s / N = 20: in phase, driven
