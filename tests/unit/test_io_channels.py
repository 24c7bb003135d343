"""The output contract's column names and units come from the SI series in one place (gearcli.io.channels):
every name docs/output.md lists, and each unit factor against its definition."""

from __future__ import annotations

import math

import numpy as np
from numpy.testing import assert_allclose

from gearcli.core.channels import Channel
from gearcli.io.channels import column, named_series


def test_columns_follow_the_contract():
    # docs/output.md, "simulate": the CSV columns of a drivetrain with a motor, couplings and bearings
    expected = {
        Channel("speed", "shaft2"): "shaft2_speed_deg_s",
        Channel("torque", "input"): "input_torque_Nmm",
        Channel("tangential_force", "stage1"): "stage1_tangential_N",
        Channel("radial_force", "stage1"): "stage1_radial_N",
        Channel("axial_force", "stage1"): "stage1_axial_N",
        Channel("penetration", "stage1"): "stage1_penetration_mm",
        Channel("dte", "stage1"): "stage1_dte_um",
        Channel("tangential_force", "stage1_planet3_ring"): "stage1_planet3_ring_tangential_N",
        Channel("dte", "stage1_planet2_sun"): "stage1_planet2_sun_dte_um",
        Channel("twist", "shaft2"): "shaft2_twist_deg",
        Channel("speed", "motor"): "motor_speed_deg_s",
        Channel("speed", "drum"): "drum_speed_deg_s",
        Channel("torque", "drive"): "motor_torque_Nm",
        Channel("speed", "drive"): "motor_speed_rpm",
        Channel("torque", "input_coupling"): "input_coupling_torque_Nm",
        Channel("torque", "load_coupling"): "load_coupling_torque_Nm",
        Channel("radial_force", "bearing4"): "bearing4_radial_N",
        Channel("axial_force", "bearing4"): "bearing4_axial_N",
    }
    assert {ch: column(ch)[0] for ch in expected} == expected


def test_unit_factors_by_definition():
    one = np.array([1.0])
    got = named_series({Channel("speed", "shaft1"): one * math.pi,  # pi rad/s = 180 deg/s
                        Channel("speed", "drive"): one * 2.0 * math.pi,  # one revolution per second = 60 rpm
                        Channel("torque", "input"): one * 2.5,  # 2.5 N m = 2500 N mm
                        Channel("penetration", "stage1"): one * 3e-6,  # 3 um = 0.003 mm
                        Channel("dte", "stage1"): one * 3e-6,  # 3 um
                        Channel("twist", "shaft2"): one * math.pi / 2,  # 90 deg
                        Channel("tangential_force", "stage1"): one * 7.0})  # N stays N
    assert_allclose([v[0] for v in got.values()], [180.0, 60.0, 2500.0, 0.003, 3.0, 90.0, 7.0], rtol=1e-15)
    assert list(got) == ["shaft1_speed_deg_s", "motor_speed_rpm", "input_torque_Nmm", "stage1_penetration_mm",
                         "stage1_dte_um", "shaft2_twist_deg", "stage1_tangential_N"]  # the series' order kept
