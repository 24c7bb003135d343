"""The input torque ripple's orders and the load fluctuation's frequencies are excitations of the modes
(crossings, Campbell data, resonance warnings), weighed by the excited body's share of the mode's kinetic energy.

The scene: a two-inertia chain. A 0.5 kg m^2 motor on a 2000 N m/rad coupling drives a spur stage 20/50 (module 4,
40 mm wide) whose mesh (~1e9 N/m) and a 1e9 N m/rad load coupling to a 200 kg m^2 drum are far stiffer than the
motor coupling, so below them the chain is two inertias on one spring (free boundary: a torque drive):

    J1 = 0.5,  J2 = J_pinion + (J_gear + J_drum) / i^2,  i = 50 / 20,
    J_pinion, J_gear = rho pi b d^4 / 32 (solid discs of the pitch diameter d = m z, rho = 7800 kg/m^3),
    f = sqrt(k (J1 + J2) / (J1 J2)) / (2 pi).

The free mode's shape has theta_1 / theta_2 = -J2 / J1, so the motor's share of its kinetic energy is
J1 theta_1^2 / (J1 theta_1^2 + J2 theta_2^2) = J2 / (J1 + J2), and the drum's (J_drum / i^2) / J2 x J1 / (J1 + J2).
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli

RHO, B = 7800.0, 0.040
J1, K, J_DRUM, I = 0.5, 2000.0, 200.0, 50 / 20
J_PINION = RHO * math.pi * B * 0.080**4 / 32
J_GEAR = RHO * math.pi * B * 0.200**4 / 32
J2 = J_PINION + (J_GEAR + J_DRUM) / I**2
F_HAND = math.sqrt(K * (J1 + J2) / (J1 * J2)) / (2 * math.pi)  # 10.14 Hz
# the mesh's compliance in series with the coupling, 2000 / (k_mesh r_b^2) = 2000 / 7.7e5 = 0.26 %, lowers the mode
# by 0.13 % (checked exactly below with the series spring); the load coupling's, 2000 / (1e9 i^2), by 1e-7
REL = 2e-3

SCENE = """
title = "two-inertia chain"
[[stage]]
normal_module_mm = 4
normal_pressure_angle_deg = 20
helix_angle_deg = 0
pinion = {{ teeth = 20, face_width_mm = 40 }}
gear   = {{ teeth = 50, face_width_mm = 40 }}
[contact]
stiffness = "iso6336"
damping_Ns_mm = 5
[input]
drive = "torque"
speed_rpm = {rpm}
torque_Nm = 40
inertia_kg_m2 = 0.5
coupling_stiffness_Nm_rad = 2000
coupling_damping_Nms_rad = 1
torque_ripple = [{{amplitude_percent = 5, order = 2}}]
[load]
torque_Nm = 100
inertia_kg_m2 = 200
coupling_stiffness_Nm_rad = 1e9
fluctuation = [{{amplitude_percent = 5, frequency_Hz = {fluct}}}]
[simulation]
duration_s = 0.05
steps = 50
"""


def _modes(tmp_path: Path, rpm: float = 600.0, fluct: float = 3.0) -> dict:
    path = tmp_path / "two.toml"
    path.write_text(SCENE.format(rpm=rpm, fluct=fluct))
    res = CliRunner().invoke(cli, ["modes", str(path), "--format", "json"])
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout)


def _crossings(mode: dict) -> dict[str, dict]:
    return {c["excitation"]: c for c in mode["crossings"]}


def test_ripple_order_crosses_the_two_inertia_mode_at_the_hand_speed(tmp_path):
    doc = _modes(tmp_path)
    rigid, mode = doc["boundaries"]["free"][:2]
    assert rigid["rigid"] and not mode["rigid"]
    assert_allclose(mode["frequency_Hz"], F_HAND, rtol=REL)  # 10.14 Hz by hand
    # the coupling and the mesh (its linearised stiffness k along the line of action, at the base radius
    # r_b = m z cos(alpha) / 2 of the pinion, as the modes JSON gives it) in series: 10.131 Hz
    k_mesh = doc["element_stiffness"][doc["elements"].index("stage 1 mesh")]
    k_series = 1.0 / (1.0 / K + 1.0 / (k_mesh * (0.040 * math.cos(math.radians(20))) ** 2))
    assert_allclose(mode["frequency_Hz"], math.sqrt(k_series * (J1 + J2) / (J1 * J2)) / (2 * math.pi), rtol=1e-4)
    c = _crossings(mode)["input torque ripple order 2"]
    # order 2 per input revolution: 2 n / 60 = f at n = 60 f / 2 rpm (by hand: 304.2 rpm)
    assert_allclose(c["input_speed_rpm"], 60 * F_HAND / 2, rtol=REL)
    assert c["source"] == "input_torque_ripple" and c["order"] == 2 and c["speed_independent"] is False
    assert c["excitation_Hz"] is None
    # the motor's share of the mode's kinetic energy, J2 / (J1 + J2) = 0.9846 by hand
    assert_allclose(c["participation"], J2 / (J1 + J2), rtol=REL)
    # the resonant gain: participation / (2 zeta) (zeta: the mode's own, from the coupling's damping mostly)
    assert_allclose(c["amplification"], c["participation"] / (2 * mode["damping_ratio"]), rtol=1e-12)
    # zeta of the coupling alone, c omega / (2 k_eff) with the two-inertia modal stiffness: the mesh adds ~nothing
    assert_allclose(mode["damping_ratio"], 1.0 * 2 * math.pi * F_HAND / (2 * K), rtol=0.02)
    # the mesh orders keep their names and sources
    mesh = _crossings(mode)["stage 1 mesh 1x"]
    assert mesh["source"] == "mesh" and mesh["order"] == 1 and mesh["speed_independent"] is False


def test_ripple_at_a_clamped_input_body_does_not_excite(tmp_path):
    """With the input body held every mode has a node there: the ripple's modal force phi_0 T is 0."""
    doc = _modes(tmp_path)
    modes = [m for m in doc["boundaries"]["clamped_input"] if not m["rigid"]]
    ripple = [c for m in modes for c in m["crossings"] if c["source"] == "input_torque_ripple"]
    assert ripple, "the slow clamped mode is crossed by the ripple order below 1.2 x nominal"
    for c in ripple:
        assert c["participation"] == 0.0 and c["amplification"] == 0.0 and c["strength"] == "weakly"


def test_load_fluctuation_is_a_horizontal_line(tmp_path):
    """A fluctuation at f Hz excites a mode within 10 % of f at every speed: its crossing has no input speed, is
    marked speed-independent, and the drum's kinetic-energy share by hand weighs it."""
    near = 1.03 * F_HAND
    doc = _modes(tmp_path, fluct=near)
    mode = doc["boundaries"]["free"][1]
    c = _crossings(mode)[f"load fluctuation {near:g} Hz"]
    assert c["input_speed_rpm"] is None and c["speed_independent"] is True
    assert c["source"] == "load_fluctuation" and c["excitation_Hz"] == pytest.approx(near, rel=1e-12)
    assert_allclose(c["participation"], (J_DRUM / I**2) / J2 * J1 / (J1 + J2), rtol=REL)  # 0.01538 by hand
    # the same at another nominal speed (the line does not move with speed)
    again = _crossings(_modes(tmp_path, rpm=150.0, fluct=near)["boundaries"]["free"][1])
    assert again[f"load fluctuation {near:g} Hz"]["input_speed_rpm"] is None
    # 15 % away: outside the margin, no crossing
    far = _modes(tmp_path, fluct=1.15 * F_HAND)["boundaries"]["free"][1]
    assert not [x for x in far["crossings"] if x["source"] == "load_fluctuation"]


def test_campbell_data_has_the_ripple_line_and_the_fixed_frequency(tmp_path):
    from gearcli import api

    near = 1.03 * F_HAND
    path = tmp_path / "two.toml"
    path.write_text(SCENE.format(rpm=600.0, fluct=near))
    loaded = api.load(str(path))
    data = api.campbell(loaded.design, api.design(loaded))
    assert ("input torque ripple order 2", 2.0) in data.orders  # a line through the origin, 2 Hz per input Hz
    assert data.fixed == ((f"load fluctuation {near:g} Hz", near),)  # a horizontal line
    by_name = {c.crossing.excitation: c for c in data.crossings if c.mode == 2}
    assert_allclose(by_name["input torque ripple order 2"].crossing.input_speed_rpm, 60 * F_HAND / 2, rtol=REL)
    assert by_name[f"load fluctuation {near:g} Hz"].crossing.speed_independent


def test_campbell_figure_draws_them(tmp_path):
    pytest.importorskip("matplotlib")
    from gearcli import api
    from gearcli.io.campbell import campbell_figure
    from gearcli.io.units import OutputUnits

    near = 1.03 * F_HAND
    path = tmp_path / "two.toml"
    path.write_text(SCENE.format(rpm=600.0, fluct=near))
    loaded = api.load(str(path))
    fig = campbell_figure(api.campbell(loaded.design, api.design(loaded)), OutputUnits())
    ax = fig.axes[0]
    labels = [line.get_label() for line in ax.get_lines()]
    assert "input torque ripple order 2" in labels and f"load fluctuation {near:g} Hz" in labels
    flat = next(line for line in ax.get_lines() if line.get_label() == f"load fluctuation {near:g} Hz")
    assert np.allclose(flat.get_ydata(), near)


def test_resonance_warning_names_the_ripple_order(tmp_path):
    """At a nominal speed of 60 f / 2 rpm the ripple's 2nd order sits on the mode: modes and simulate warn,
    worded like a mesh order's warning, naming the excitation."""
    rpm = 60 * F_HAND / 2
    doc = _modes(tmp_path, rpm=rpm)
    (w,) = [w for w in doc["warnings"] if w["code"] == "resonance"]
    assert w["excitation"] == "input torque ripple order 2" and w["source"] == "input_torque_ripple"
    assert w["stage"] is None and w["mode"] == 2 and w["strength"] == "strongly"
    assert_allclose(w["excitation_Hz"], 2 * rpm / 60, rtol=1e-12)
    assert w["message"].startswith("resonance: the input torque ripple order 2 (")
    assert "of mode 2" in w["message"] and "strongly excited" in w["message"]
    res = CliRunner().invoke(cli, ["simulate", str(tmp_path / "two.toml"), "--format", "json"])
    assert res.exit_code == 0, res.output
    sim = json.loads(res.stdout)
    assert [x["message"] for x in sim["warnings"] if x["code"] == "resonance"] == [w["message"]]


def test_kinetic_share_is_zero_at_a_node():
    """A symmetric 3-body free mode (1, 0, -1, equal end inertias) has a node at its middle body: no share there."""
    from types import SimpleNamespace

    from gearcli.model.modes import kinetic_share

    lay = SimpleNamespace(inertias=(2.0, 5.0, 2.0))
    assert kinetic_share(lay, (1.0, 0.0, -1.0), 1) == 0.0  # type: ignore[arg-type]
    assert kinetic_share(lay, (1.0, 0.0, -1.0), 0) == pytest.approx(0.5)  # type: ignore[arg-type]
