"""A plug-in stage that is no gear pair and gives no model of its own (``stage_model`` None: placed as a pair of
its line, docs/plugins.md "Losses") has no mesh orders: docs/plugins.md ("What a kind that is no gear pair does not
get: ... mesh orders in ``modes``") and ARCHITECTURE.md (its connector's role is ``"stage"``). Until 2026-12-01 its
line was placed as a gear mesh, whose orders came from the line's default ``pinion_teeth`` (20): ``modes`` listed
``stage 1 mesh hx`` crossings for a chain drive and ``design`` warned of a resonance with a tooth frequency that
does not exist.

The scene: ``plug_chain.py``'s chain alone (lossless), its model facet swapped for one whose ``stage_model`` is
None, its driver speed-driven. The reference is written here: with the input held (``clamped_input``) the driven
sprocket is one degree of freedom on the chain's stiffness, omega^2 = k r_2^2 / J_2, r_2 = z_2 p / (2 pi); at
740 rpm a 20-tooth order 20 n / 60 = 246.7 Hz would sit 0.2 % above that mode (246.1 Hz)."""

from __future__ import annotations

import json
import math
from dataclasses import replace

import plug_chain as pc
import pytest
import tomli_w
from click.testing import CliRunner

from gearcli.cli import cli
from gearcli.stages import kinds

Z1, Z2, PITCH, K, J1, J2, N_IN, T_L = 17, 51, 19.05, 2.0e7, 0.02, 0.2, 740.0, 300.0


class PairedChainModel(pc.ChainModelKind):
    """The chain's model facet without a stage model: the stage is the chain's pair of its (lossless) line."""

    def line(self, cfg, st, k, pair_mesh):
        return replace(super().line(cfg, st, k, pair_mesh), efficiency=st.efficiency)

    def stage_model(self, cfg, st, k, mesh):
        return None


@pytest.fixture
def paired_chain():
    pc.register()
    kinds.withdraw(pc.KIND, "model")
    kinds.provide(pc.KIND, "model", PairedChainModel())
    yield
    pc.withdraw()


def _scene(tmp_path):
    stage = {"type": pc.KIND, "driver_teeth": Z1, "driven_teeth": Z2, "pitch_mm": PITCH, "chain_efficiency": 1.0,
             "stiffness_N_m": K, "damping_Ns_m": 2000.0, "driver_inertia_kg_m2": J1, "driven_inertia_kg_m2": J2}
    doc = {"title": "a chain placed as its line", "stage": [stage], "input": {"speed_rpm": N_IN, "ramp_s": 0.05},
           "load": {"torque_Nm": T_L, "ramp_s": 0.05}, "simulation": {"duration_s": 0.3, "steps": 600}}
    path = tmp_path / "chain.toml"
    path.write_bytes(tomli_w.dumps(doc).encode())
    return path


def test_a_line_placed_stage_has_no_mesh_orders(paired_chain, tmp_path):
    path = _scene(tmp_path)
    r2 = Z2 * PITCH * 1e-3 / (2.0 * math.pi)
    f_hand = math.sqrt(K * r2 * r2 / J2) / (2.0 * math.pi)  # 246.1 Hz
    assert abs(20.0 * N_IN / 60.0 / f_hand - 1.0) < 0.01  # the phantom 20-tooth order would sit on the mode

    res = CliRunner().invoke(cli, ["modes", str(path), "--format", "json"])
    assert res.exit_code == 0, res.output
    modes = json.loads(res.stdout)
    held = modes["boundaries"]["clamped_input"]
    assert len(held) == 1
    assert held[0]["frequency_Hz"] == pytest.approx(f_hand, rel=1e-9)
    sources = [c["source"] for m in held + modes["boundaries"]["free"] for c in m["crossings"]]
    assert "mesh" not in sources, sources

    res = CliRunner().invoke(cli, ["design", str(path), "--format", "json"])
    assert res.exit_code == 0, res.output
    warnings = json.loads(res.stdout)["warnings"]
    assert not [w for w in warnings if "resonance" in w["message"]], warnings


def test_a_line_placed_stage_still_carries_its_force(paired_chain, tmp_path):
    """The stage's statistics are its connector's as before: the chain force T_L / r_2 at rest in the window."""
    path = _scene(tmp_path)
    res = CliRunner().invoke(cli, ["simulate", str(path), "--format", "json"])
    assert res.exit_code == 0, res.output
    stage = json.loads(res.stdout)["summary"]["stages"][0]
    r2 = Z2 * PITCH * 1e-3 / (2.0 * math.pi)
    assert stage["static_chain_force_N"] == pytest.approx(T_L / r2, rel=1e-12)
    assert stage["chain_force_N"]["mean"] == pytest.approx(T_L / r2, rel=1e-4)
