"""Synthetic designs, simulations and a stand-in solver for the report tests (no tests here).

The stand-in solver has a known error law, error = C_method * rtol^p_method on every compared
quantity, so the accuracy study's errors, flags and recommendation can be checked by hand.
"""

from __future__ import annotations

import math

import numpy as np

from gearcli.core.channels import Channel
from gearcli.results import DesignResult, GearResult, ShaftResult, StageResult, StaticForces
from gearcli.simulate.results import ChannelStats, EnergyBalance, SimulationResult, SolverStats, StageDynamics


def _gear(teeth: int, speed: float) -> GearResult:
    return GearResult(teeth, "spur", 0.0, 50.0, 10.0 * teeth, 9.4 * teeth, 10.0 * teeth + 20, 10.0 * teeth - 25,
                      speed, speed / 6, 1e5, 0.1, False)


def fake_design(ratios=(2.0, 3.0), input_speed=3600.0, ft=(1000.0, 2800.0)) -> DesignResult:
    stages, speed = [], input_speed
    for k, (i, f) in enumerate(zip(ratios, ft, strict=True), start=1):
        pin, gear = _gear(20, speed), _gear(int(20 * i), speed / i)
        stages.append(StageResult(
            index=k, ratio=i, efficiency=1.0, normal_module_mm=10, transverse_module_mm=10,
            normal_pressure_angle_deg=20, transverse_pressure_angle_deg=20, working_pressure_angle_deg=20,
            helix_angle_deg=0, base_helix_angle_deg=0, center_distance_mm=100, transverse_base_pitch_mm=29.5,
            face_width_mm=50, contact_ratio_transverse=1.6, overlap_ratio=0, contact_ratio_total=1.6,
            mesh_frequency_Hz=20 * speed / 360, equivalent_radius_mm=60, effective_modulus_MPa=1.13e5,
            hertz_stiffness_N_mm1_5=1e6, static_approach_mm=0.01, linearised_stiffness_N_mm=1e5,
            static_force_N=StaticForces(f, f * math.tan(math.radians(20)), 0.0, f / math.cos(math.radians(20))),
            iso6336_single_pair_stiffness_N_mm_um=14, iso6336_mesh_stiffness_N_mm_um=20, backlash_mm=0,
            pinion=pin, gear=gear))
        speed /= i
    shafts = [ShaftResult(1, input_speed, input_speed / 6, 1e5, 0.1)]
    shafts += [ShaftResult(s.index + 1, s.gear.speed_deg_s, s.gear.speed_rpm, 1e5, 0.1) for s in stages]
    total = float(np.prod(ratios))
    return DesignResult("fake", tuple(stages), tuple(shafts), total, input_speed, input_speed / total,
                        input_speed / total / 6, 1e5, 1e5 * total, ())


def _stats(x: np.ndarray) -> ChannelStats:
    return ChannelStats(float(np.mean(x)), float(np.min(x)), float(np.max(x)), float(np.std(x)))


def fake_simulation(design: DesignResult, *, speed_err=0.0, force_err=0.0, peak_err=0.0, method="DOP853",
                    rtol=1e-6, wall_s=1.0, nfev=1000, ripple_Hz=160.0, n=2001, duration=0.5) -> SimulationResult:
    """Speeds at the design values (times 1 + speed_err on the output), F_t = static (1 + force_err)
    plus a 5 % sine at ``ripple_Hz``; peak = 1.5 static (1 + peak_err)."""
    t = np.linspace(0.0, duration, n)
    window = (0.25, duration)
    mask = t >= window[0]
    channels, dyn = {}, []
    for sh in design.shafts:
        factor = 1 + speed_err if sh.index == len(design.shafts) else 1.0
        channels[Channel("speed", f"shaft{sh.index}")] = np.full_like(t, math.radians(sh.speed_deg_s * factor))
    for st in design.stages:
        f0 = st.static_force_N.tangential * (1 + force_err)
        ft = f0 * (1 + 0.05 * np.sin(2 * np.pi * ripple_Hz * t))
        channels[Channel("tangential_force", f"stage{st.index}")] = ft
        channels[Channel("radial_force", f"stage{st.index}")] = ft * math.tan(math.radians(20))
        channels[Channel("axial_force", f"stage{st.index}")] = 0 * ft
        channels[Channel("penetration", f"stage{st.index}")] = np.full_like(t, 0.01e-3)
        peak = 1.5 * st.static_force_N.tangential * (1 + peak_err)
        dyn.append(StageDynamics(st.index, _stats(ft[mask]), _stats(channels[Channel("radial_force", f"stage{st.index}")][mask]),
                                 _stats(0 * ft[mask]), _stats(np.full(mask.sum(), 0.01)),
                                 st.static_force_N.tangential, peak, 0.1, 1.5))
    out_speed = design.output_speed_deg_s * (1 + speed_err)
    solver = SolverStats(method, method, "as requested", rtol, {"speed_rad_s": rtol}, nfev, 0, 0, nfev // 12,
                         wall_s, 1e-7, 0, "ok")
    return SimulationResult(t, channels, window, design.input_speed_deg_s / out_speed, out_speed,
                            design.input_speed_deg_s, tuple(dyn), solver,
                            EnergyBalance(1.0, 1.0, 0.0, 0.0, 0.0, 1e-7), (), (160.0, 900.0))


LAW = {"DOP853": (3.0, 1.0, 0.2), "Radau": (30.0, 1.0, 0.8), "RK45": (10.0, 1.0, 0.5),
       "BDF": (60.0, 1.0, 8.0)}  # C, p, wall at 1e-6


class FakeSolver:
    """error = C rtol^p on every compared quantity; wall time grows as rtol^(-1/5)."""

    def __init__(self, design, auto="DOP853"):
        self.design, self.auto, self.calls = design, auto, []

    def __call__(self, method: str, rtol: float):
        self.calls.append((method, rtol))
        used = self.auto if method == "auto" else method
        c, p, wall = LAW[used]
        err = c * rtol**p
        return fake_simulation(self.design, speed_err=err, force_err=-err, peak_err=err, method=used, rtol=rtol,
                               wall_s=wall * (1e-6 / rtol) ** 0.2, nfev=int(1000 * (1e-6 / rtol) ** 0.2))




def fake_cfg():
    """A DesignFile with the fake design's two stages (the stand-in solver ignores it)."""
    from gearcli.config.schema import DesignFile

    return DesignFile.model_validate({
        "stage": [{"normal_module_mm": 10, "pinion": {"teeth": 20, "face_width_mm": 50},
                   "gear": {"teeth": 40, "face_width_mm": 50}},
                  {"normal_module_mm": 10, "pinion": {"teeth": 20, "face_width_mm": 50},
                   "gear": {"teeth": 60, "face_width_mm": 50}}],
        "input": {"speed_deg_s": 3600.0}, "load": {"torque_Nmm": 1e5}})


def fake_report(quick: bool = False, rtols=(1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9)):
    from gearcli.report import LadderSpec, build_report

    design = fake_design()
    solver = FakeSolver(design)

    def simulate(cfg_, design_, *, method=None, rtol=None, want_series=True, error_estimate=None):
        return solver(method or cfg_.simulation.method, rtol or cfg_.simulation.rtol)

    return build_report(fake_cfg(), design, quick=quick, spec=LadderSpec(rtols=rtols), simulate=simulate)
