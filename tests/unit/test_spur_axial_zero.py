"""A spur stage's axial force is zero, also where the mesh force reverses: F_a = F_t tan(0) = 0 (by hand), never the
negative zero a negative F_t times tan 0 gives in IEEE arithmetic, which the series CSV printed as "-0" and the
report's force table as a window min / max of "-0"."""

from __future__ import annotations

import math

import numpy as np
from numpy.testing import assert_allclose, assert_array_equal

from gearcli import api
from gearcli.io.report_sections import g
from gearcli.model.assembly import Layout
from gearcli.model.outputs import tooth_forces
from gearcli.scene import spec_from_design


def test_a_spur_stage_has_a_zero_axial_force_on_either_flank():
    loaded, design = api.load_and_design("configs/extreme/spur.toml", [])
    lay = Layout.of(spec_from_design(loaded.design, design))
    line = np.array([-2.0e4, -1.0, -0.0, 0.0, 3.5e3])
    for out in (None, np.empty((3, line.size))):
        ft, fr, fa = tooth_forces(lay, 0, line, out=out)
        alpha = math.radians(loaded.design.stage[0].normal_pressure_angle_deg)  # beta = 0: alpha_t = alpha_n
        assert_allclose(ft, line * math.cos(alpha), rtol=1e-15)
        assert_allclose(fr, line * math.cos(alpha) * math.tan(alpha), rtol=1e-15)
        assert_array_equal(fa, 0.0)
        assert not np.any(np.signbit(fa))


def test_the_report_prints_no_negative_zero():
    assert g(-0.0) == "0" and g(0.0) == "0" and g(-1.5) == "-1.5"

