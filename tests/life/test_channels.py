"""Bearing reaction channels: the same statics as the design, sample by sample."""

from __future__ import annotations

import json
import math

import numpy as np
from click.testing import CliRunner
from numpy.testing import assert_allclose

from gearcli.cli import cli
from gearcli.core.channels import Channel
from gearcli.design.shafts import stage_layout
from gearcli.simulate.bearings import reaction_series
from tests.life.scenes import COUNTERSHAFT, design_of


def test_channels_at_the_static_force_equal_the_design_reactions():
    """Series of the design's static F_t give the design's reactions; twice the force gives twice the
    reactions (they are linear in the mesh forces)."""
    cfg, d = design_of(COUNTERSHAFT)
    lay = stage_layout(cfg, d.stages)
    ft = {Channel("tangential_force", f"stage{s.index}"): np.array([1.0, 2.0]) * s.static_force_N.tangential
          for s in d.stages}
    r = reaction_series(lay, d, ft)
    for j, b in enumerate(d.bearings):
        assert_allclose(r[j, :, 0], [b.radial_y_N, b.radial_z_N, b.axial_N], rtol=1e-9, atol=1e-9)
        assert_allclose(r[j, :, 1], 2 * r[j, :, 0], rtol=1e-12, atol=1e-9)


def test_simulate_reports_bearing_channels_and_window_statistics(tmp_path):
    """A lossless run's window mean forces equal the static ones, so the bearings' mean radial load does too
    (to the run's accuracy: the window mean of F_t within 1e-3 of the static value)."""
    path = tmp_path / "countershaft.toml"
    path.write_text(COUNTERSHAFT + "\n[simulation]\nduration_s = 0.2\nsteps = 400\n")
    res = CliRunner().invoke(cli, ["simulate", str(path), "--format", "json", "--series"])
    assert res.exit_code == 0, res.output
    doc = json.loads(res.stdout)
    _, d = design_of(COUNTERSHAFT)
    bearings = doc["summary"]["bearings"]
    assert [b["shaft"] for b in bearings] == [2, 2]
    for b, static in zip(bearings, d.bearings, strict=True):
        assert_allclose(b["radial_N"]["mean"], static.radial_N, rtol=2e-3)
        assert math.isfinite(b["axial_N"]["std"])
    assert "bearing1_radial_N" in doc["series"] and "bearing2_axial_N" in doc["series"]
