"""An unloaded planetary stage at constant speed is at rest (F_t = 0 but for round-off, 1e-10 N): its window
statistics refer to the force the run resolves, not to the rms of that round-off (trial tr22b: sun 24 / planets 30
(3) / ring 84 held at zero load warned "F_t mean, min, max, std, spectrum peaks not resolved by Radau ... 1.9 of the
rms 4.381e-10 N of the unloaded stage's F_t" and suggested a tighter rtol: the planets' worst-planet estimate took no
floor, a parallel stage's does).

Hand reference (gearcli.simulate.estimate.force_floors_N's definition, from the design's numbers): the least force a
stage's targets refer to is the mesh law's tangent times the deflection tolerance, e K h^e rtol along the line of
action with h = 1 µm (no load, no backlash), on the reference circle cos α_t of it (spur).
"""

from __future__ import annotations

import math

import pytest

from gearcli import api
from gearcli.diagnostics import STATISTICS_UNDERSAMPLED, STATISTICS_UNRESOLVED
from tests.reference import test_planetary_worst_planet as worst  # its stage, unloaded and without position errors

IDLE = (worst.SCENE.replace(f", position_error_um = [0.0, {worst.E_UM}, 0.0]", "")
        .replace(f"torque_Nm = {worst.T_LOAD}", "torque_Nm = 0.0").replace("rtol = 1e-9\n", ""))


def test_an_idle_planetary_stage_is_at_rest_not_unresolved(tmp_path):
    assert "position_error_um" not in IDLE and "torque_Nm = 0.0" in IDLE and "rtol" not in IDLE
    (tmp_path / "idle.toml").write_text(IDLE)
    loaded, design = api.load_and_design(str(tmp_path / "idle.toml"))
    result = api.simulate(loaded.design, design)
    st, ds = result.stages[0], design.stages[0]
    law = ds.mesh_stiffness
    rtol = result.solver.rtol
    floor = law.exponent * law.K * (1e-3) ** law.exponent * rtol * math.cos(math.radians(ds.transverse_pressure_angle_deg))
    assert st.error_estimate.reference_N == pytest.approx(floor, rel=1e-9)
    assert st.sampling_error.reference_N == pytest.approx(floor, rel=1e-9)
    assert all(max(abs(p.sun.tangential_N.min), abs(p.sun.tangential_N.max)) < 1e-3 * floor for p in st.planets)
    codes = {d.code for d in result.diagnostics}
    assert STATISTICS_UNRESOLVED not in codes and STATISTICS_UNDERSAMPLED not in codes
