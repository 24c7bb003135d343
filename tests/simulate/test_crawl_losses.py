"""A lossy mesh at crawl speed (0.003 rpm): the run-up's vibration swings the pitch line through zero at ~0.2 m/s
while the nominal pitch-line speed is ~1e-5 m/s, so the power-flow sign of the mesh's losses flips with every
swing. ``auto`` ran DOP853 there, which stopped after 3.4e6 evaluations at 0.12 s of 0.3 s (94 s).

References: the rated efficiency eta (a settled run passes on eta of the driving side's force: f_b / f_a = eta,
the module text of ``gearcli.model.elements.mesh.loss_factors``); the same scene at the nominal speed of its
design (1500 rpm), where the vibration never reverses the power flow; a run of the same model at rtol 1e-9.
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from gearcli import api
from gearcli.core.methods import EXPLICIT_METHOD, IMPLICIT_METHOD
from gearcli.model import TorsionalModel
from gearcli.model.assembly import loss_speeds
from gearcli.simulate.choice import choose_method

ETA = 0.98
SCENE = f"""
title = "one lossy stage on couplings"
[[stage]]
efficiency = {ETA}
normal_module_mm = 3
helix_angle_deg = 15
gear   = {{ teeth = 61, face_width_mm = 38, hand = "right" }}
pinion = {{ teeth = 20, face_width_mm = 40, hand = "left" }}

[materials.steel]  # the scene of trial tr20e, its transmission error and backlash left out
poisson_ratio = 0.3
youngs_modulus_MPa = 2.06e5
density_kg_m3 = 7850

[input]
speed_rpm = 1500
ramp_s = 0.1
inertia_kg_m2 = 0.02
coupling_stiffness_Nm_rad = 5e3
coupling_damping_Nms_rad = 1

[load]
torque_Nm = 300
ramp_s = 0.1
inertia_kg_m2 = 2
coupling_stiffness_Nm_rad = 2e4
coupling_damping_Nms_rad = 10

[simulation]
duration_s = 0.15
steps = 300
rtol = 1e-5
"""


def _loaded(tmp_path: Path, rpm: float):
    path = tmp_path / "lossy.toml"
    path.write_text(SCENE)
    loaded = api.load(str(path), [f"input.speed_rpm={rpm}"])
    return loaded, api.design(loaded)


def _model(tmp_path: Path, rpm: float) -> TorsionalModel:
    loaded, result = _loaded(tmp_path, rpm)
    return TorsionalModel(api.model_spec(loaded.design, result))


@pytest.mark.parametrize("rpm", [1500.0, 0.003])
def test_a_settled_run_loses_the_rated_share_at_any_speed(tmp_path: Path, rpm: float) -> None:
    """The sign's width grows with the vibration at crawl but stays narrow against the nominal pitch-line speed:
    at that speed the driven side carries eta of the driving side's force (to 1e-9 of it)."""
    lay = _model(tmp_path, rpm).layout
    (x,) = [c for c in lay.connectors if c.lossy]
    F, v, v_vib = loss_speeds(lay.spec, lay.bodies, x)
    assert (v_vib > v) == (rpm < 1.0)  # crawl: the vibration outruns the nominal speed
    f_a, f_b, *_ = x.element.loss_factors(x.params, F, v, v)  # pinion and gear at the nominal pitch-line speed
    assert f_b / f_a == pytest.approx(ETA, rel=1e-9)


def test_auto_offers_no_explicit_method_where_the_sign_flips(tmp_path: Path) -> None:
    crawl, nominal = _model(tmp_path, 0.003), _model(tmp_path, 1500.0)
    choice = choose_method(crawl.spec, 0.3, "auto", 1e-5, layout=crawl.layout)
    assert choice.method == IMPLICIT_METHOD
    assert "power-flow sign flips" in choice.reason and choice.explicit_barred
    assert choose_method(nominal.spec, 0.3, "auto", 1e-5, layout=nominal.layout).explicit_barred == ""
    assert choose_method(crawl.spec, 0.3, EXPLICIT_METHOD, 1e-5, layout=crawl.layout).explicit_barred == ""


def test_the_crawl_run_finishes_within_its_stated_error(tmp_path: Path) -> None:
    loaded, result = _loaded(tmp_path, 0.003)
    run = api.simulate(loaded.design, result, want_series=False)
    assert run.solver.method == IMPLICIT_METHOD
    assert all(not str(c["to"]).startswith(EXPLICIT_METHOD) for c in run.solver.course_changes)
    ref = api.simulate(loaded.design, result, method=IMPLICIT_METHOD, rtol=1e-9, want_series=False)
    got, want = run.stages[0], ref.stages[0]
    err = got.error_estimate
    assert err is not None
    for name in ("mean", "min", "max"):
        allowed = 4.0 * getattr(err.tangential_N, name) + 20 * run.solver.rtol * err.reference_N
        assert math.isclose(getattr(got.tangential_N, name), getattr(want.tangential_N, name), rel_tol=0.0,
                            abs_tol=allowed), name
