"""A load that drives the train with a torque growing with speed (a negative `[load] torque_Nm` with
`speed_exponent = 2`) against a torque drive has no stable balance: the train runs away and its speed grows without
bound in a finite time. `simulate` failed there with "the step size collapsed ... likely a violent contact impact or a
discontinuous stiffness — try method = "Radau"" (on a Radau run too), and `life` failed a duty point with a negative
torque on a fan-law file the same way. It now says that the train ran away, which body and how fast.

Hand model (DESIGN sections 4, 9; docs/physics.md "Stage efficiency in the dynamics"): one spur pair, i = 2, both
bodies free, started at their nominal speeds; the drive 10 N m, the load T_L = T (w/w_n)|w/w_n| with T = -400 N m on
the gear, both from t = 0. The gear drives the pinion (power from the load), so the pinion side gets eta f: rigidly,
(J_p + eta J_g / i^2) w' = T_in + eta |T| / i (w/w_n)^2, which from w_n reaches infinity at
t* = J_eff / sqrt(a b) (pi/2 - atan(w_n sqrt(b / a))), a = T_in, b = eta |T| / (i w_n^2). The stiff mesh follows the
rigid train to its blow-up, so the run fails between the rigid train's passing 10x its nominal speed
(the runaway the message names) and its blow-up.
"""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

from click.testing import CliRunner

from gearcli.cli import cli

SCENE = """
title = "a fan-law load that drives the train, against a torque drive"
contact = { stiffness = 4.0e5, exponent = 1.0, damping_ratio = 0.05 }
input = { drive = "torque", speed_rpm = 600, torque_Nm = 10, ramp_s = 0 }
load = { torque_Nm = -400, speed_exponent = 2, ramp_s = 0 }
simulation = { duration_s = 0.05, steps = 500 }
[[stage]]
efficiency = 0.96
pinion.teeth = 20
gear.teeth = 40
normal_module_mm = 4
pinion.inertia_kg_m2 = 0.02
gear.inertia_kg_m2 = 0.3
normal_pressure_angle_deg = 20
pinion.face_width_mm = 40
gear.face_width_mm = 40
"""


def _rigid_time_s(speed_factor: float) -> float:
    """The rigid train's time from w_n to speed_factor x w_n (math.inf: its blow-up)."""
    eta, i, j_p, j_g, t_in, t_load = 0.96, 2.0, 0.02, 0.3, 10.0, 400.0
    w_n = 600 * math.pi / 30
    j_eff = j_p + eta * j_g / i**2
    a, b = t_in, eta * t_load / (i * w_n**2)
    reach = math.pi / 2 if math.isinf(speed_factor) else math.atan(speed_factor * w_n * math.sqrt(b / a))
    return j_eff / math.sqrt(a * b) * (reach - math.atan(w_n * math.sqrt(b / a)))


def test_a_train_that_runs_away_is_named_at_its_blow_up(tmp_path: Path) -> None:
    path = tmp_path / "runaway.toml"
    path.write_text(SCENE, encoding="utf-8")
    out = tmp_path / "run.json"
    res = CliRunner().invoke(cli, ["simulate", str(path), "--format", "json", "-q", "-o", str(out)])
    assert res.exit_code == 1, res.output
    assert not out.exists()  # a failed run leaves no file
    message = res.output
    assert "the train ran away" in message and "no integrator setting helps" in message, message
    assert "violent contact" not in message
    # where it stopped: after the rigid train passed 10x its nominal speed (0.02659 s), at its blow-up (0.02960 s)
    t_fail = float(message.split("stopped at t = ")[1].split(" s")[0])
    assert _rigid_time_s(10.0) < t_fail < _rigid_time_s(math.inf) * (1 + 1e-3), t_fail
    assert float(re.search(r"([0-9.e+]+)x its nominal", message).group(1)) > 10.0


def test_design_warns_that_an_overhauling_fan_load_has_no_stable_balance(tmp_path: Path) -> None:
    """Balanced at the nominal speed (the drive's torque the load's reflected through the reversed mesh, T_L eta / i =
    -400 x 0.96 / 2 = -192 N m), the train still has no stable balance: d(T_L)/dn = 2 T n / n_0^2 < 0 pushes it away
    from n_0 either way. `design` said nothing (the drive balanced within 1 %); it now warns."""
    path = tmp_path / "balanced.toml"
    path.write_text(SCENE.replace("torque_Nm = 10,", "torque_Nm = -192,"), encoding="utf-8")
    res = CliRunner().invoke(cli, ["design", str(path), "--format", "json", "-q"])
    assert res.exit_code == 0, res.output
    doc = json.loads(res.stdout)
    assert math.isclose(doc["input_torque_Nm"], -400 * 0.96 / 2, rel_tol=1e-12)
    found = [w for w in doc["warnings"] if w.get("check") == "torque_drive_balance"]
    assert len(found) == 1, doc["warnings"]
    assert math.isclose(found[0]["required_input_torque_Nm"], -192.0, rel_tol=1e-12)
    assert "no speed is a stable balance" in found[0]["message"] and "in a finite time" in found[0]["message"]


def _ran_away_text(path: Path, *sets: str) -> str:
    """ran_away's text for a run of the file's model whose last sample has every free body at 20x its nominal speed."""
    import numpy as np

    from gearcli.config import load_design
    from gearcli.design import compute_design
    from gearcli.model import TorsionalModel
    from gearcli.scene import spec_from_design
    from gearcli.simulate.failures import ran_away
    from gearcli.simulate.solver import STATUS_FAILED, Integration

    cfg = load_design(str(path), list(sets)).design
    model = TorsionalModel(spec_from_design(cfg, compute_design(cfg)))
    y = np.zeros((model.initial_state().size, 2))
    for i, w in zip(model.layout.free_bodies, model.speed_scales_rad_s(), strict=True):
        j = model.layout.state.omega(i)
        if j is not None:
            y[j, 1] = 20.0 * w
    run = Integration(np.array([0.0, 0.1]), y, "DOP853", 1e-6, np.ones(y.shape[0]), 100, 0, 0, 10, 0.0,
                      STATUS_FAILED, "step size", 0.1)
    text = ran_away(model, run)
    assert text is not None and "20x its nominal" in text
    return text


def test_the_runaway_cause_follows_the_drive(tmp_path: Path) -> None:
    # A speed drive holds the input: a body that ran away took its energy from the train's own response (the seed
    # with no mesh damping and a 0.99 stiffness harmonic under 10 N m, found by a fuzz, was told "the drive does not
    # hold the load ... a negative [load] torque ... torque drive"). The overhauling fan load keeps its cause; a
    # torque drive against a constant load that it cannot hold is told to check the torques, not the speed law.
    root = Path(__file__).resolve().parents[2]
    seed = _ran_away_text(root / "configs" / "concrete_mixer.toml")
    assert "with the input held at its speed" in seed and "negative [load] torque" not in seed
    path = tmp_path / "runaway.toml"
    path.write_text(SCENE, encoding="utf-8")
    fan = _ran_away_text(path)
    assert "negative [load] torque on a speed law" in fan and "a torque drive does not brake it" in fan
    constant = _ran_away_text(path, "load.speed_exponent=0")
    assert "negative [load] torque" not in constant and "check the drive's and the load's torques" in constant
