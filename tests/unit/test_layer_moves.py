"""The pieces issue 34 moved to their layer still say the same thing: Willis' speeds (design) against the
schema's ratio (config), the design file's output units (io), the bearing channels of ``api.simulate``."""

from __future__ import annotations

from pathlib import Path

import pytest
from numpy.testing import assert_allclose

from gearcli.config import load_design
from gearcli.design.planetary_balance import willis_speeds

ROOT = Path(__file__).resolve().parents[2]
MEMBERS = ("sun", "carrier", "ring")


@pytest.mark.parametrize("fixed", MEMBERS)
@pytest.mark.parametrize("driven", MEMBERS)
def test_the_schema_s_ratio_is_willis_speed_ratio(fixed, driven):
    """config keeps |w_in / w_out| in closed form (it cannot import design); design's signed Willis speeds give
    the same ratio for every held and driven member; the textbook cases by hand (u = z_r / z_s = 72/24 = 3):
    ring held, sun in, carrier out: 1 + u = 4; carrier held, sun in, ring out: u = 3; sun held, ring in,
    carrier out: (1 + u) / u = 4/3."""
    if fixed == driven:
        return
    stage = next(s for s in load_design(str(ROOT / "configs" / "planetary_stage.toml")).design.stage
                 if getattr(s, "type", "parallel") == "planetary")
    stage = stage.model_copy(update={"fixed": fixed, "input": driven,
                                     "sun": stage.sun.model_copy(update={"teeth": 24}),
                                     "ring": stage.ring.model_copy(update={"teeth": 72})})
    w = willis_speeds(24, 72, fixed, driven)
    assert w[driven] == 1.0 and w[fixed] == 0.0
    assert_allclose(stage.speed_ratio, abs(w[driven] / w[stage.output]), rtol=1e-14, err_msg="same kinematics")
    by_hand = {("ring", "sun"): 4.0, ("ring", "carrier"): 0.25, ("carrier", "sun"): 3.0, ("carrier", "ring"): 1 / 3,
               ("sun", "ring"): 4 / 3, ("sun", "carrier"): 3 / 4}
    assert_allclose(stage.speed_ratio, by_hand[(fixed, driven)], rtol=1e-14)


def test_a_design_file_s_output_units_are_its_keys():
    """io.units.key_units (moved from scene): the input's speed key and the load's torque key name the units."""
    from gearcli.io.units import key_units, of_design_file

    cfg = load_design(str(ROOT / "configs" / "mixer_duty.toml")).design  # speed_rpm, torque_Nm
    assert key_units(cfg) == ("rpm", "Nm")
    assert (of_design_file(cfg).speed, of_design_file(cfg).torque) == ("rpm", "Nm")


def test_api_simulate_returns_the_bearing_channels_the_cli_prints():
    """The bearing reactions are computed in the facade's ``simulate`` (not only in ``simulate_file``): a scene
    with [[bearing]] tables gets each bearing's radial and axial series and window statistics, and its results
    in the units of its keys."""
    from gearcli import api
    from gearcli.core.channels import Channel
    from gearcli.design import compute_design

    loaded = load_design(str(ROOT / "configs" / "mixer_duty.toml"))
    cfg = loaded.design.model_copy(update={"simulation": loaded.design.simulation.model_copy(
        update={"duration_s": 0.1, "steps": 400, "window_start_s": 0.05})})
    design = compute_design(cfg)
    result = api.simulate(cfg, design)
    n = len(cfg.bearing)
    assert n >= 2
    for j in range(1, n + 1):
        for quantity in ("radial_force", "axial_force"):
            assert result.series[Channel(quantity, f"bearing{j}")].shape == result.time_s.shape
    assert result.extra is not None and len(result.extra["bearings"]) == n
    assert result.units == ("rpm", "Nm")
