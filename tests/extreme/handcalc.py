"""Hand calculations for the extreme-scene catalogue, straight from a design file's TOML.

This module deliberately shares no code with ``gearcli``: it reads the TOML with ``tomllib`` and
re-derives, from textbook formulas (docs/physics.md), what a rigid, lossless gear train
must do. The catalogue checks the simulation against these numbers, so a wrong formula in the product
cannot hide behind the same wrong formula in the test.

- pitch radius r = z m_n / (2 cos beta) (ISO 21771); stage ratio i = z_gear / z_pinion
- static forces on the pitch circle: T_gear,k = T_L / (i_{k+1} ... i_n), F_t,k = T_gear,k / r_gear,k,
  F_n = F_t / (cos alpha_n cos beta) (equal to F_bt / cos beta_b: cos alpha_t cos beta_b = cos alpha_n cos beta)
- Hertz constant K = 4/3 sqrt(R) E*, 1/R = 1/r_1 + 1/r_2 (pitch radii, mm), 1/E* = sum (1 - nu^2)/E
- static approach h_0 = (F_n / K)^(1/e); mesh potential energy K p^(e+1) / (e+1)
- solid-disc inertia J = pi rho b r^4 / 2 (pitch radius, face width) unless inertia_kg_m2 is given;
  shaft k+1 carries gear k and pinion k+1
- rigid run-up: shaft speeds rho_i w_1 (rho_i = 1 / (i_1 ... i_{i-1})); the torque on gear k accelerates
  everything after it and carries the load, T_gear,k = (sum_{i>k} J_i rho_i^2 alpha_1 + T_L rho_n) / rho_{k+1}
- Adams STEP(t, 0, 0, T, v) = v s^2 (3 - 2 s), s = t / T clamped to [0, 1]; T = 0: v from t = 0
"""

from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass
from pathlib import Path

import numpy as np

SEED_MATERIAL = {"density_kg_m3": 7800.0, "youngs_modulus_MPa": 2.07e5, "poisson_ratio": 0.29}


def read(path: str | Path) -> dict:
    with open(path, "rb") as fh:
        return tomllib.load(fh)


def step(t, ramp_s: float, value: float):
    """STEP(t, 0, 0, ramp_s, value) and its time derivative."""
    t = np.asarray(t, dtype=float)
    if ramp_s <= 0:
        return np.full(t.shape, float(value)), np.zeros(t.shape)
    s = np.clip(t / ramp_s, 0.0, 1.0)
    return value * s * s * (3 - 2 * s), value * 6 * s * (1 - s) / ramp_s


@dataclass(frozen=True)
class Train:
    """What a rigid, lossless train does, from the design file alone. Lengths in mm, forces in N."""

    doc: dict

    # ----------------------------------------------------------------------------- geometry
    @property
    def stages(self) -> list[dict]:
        return self.doc["stage"]

    def beta(self, k: int) -> float:
        return math.radians(self.stages[k].get("helix_angle_deg", 0.0))

    def alpha_n(self, k: int) -> float:
        return math.radians(self.stages[k].get("normal_pressure_angle_deg", 20.0))

    def pitch_radius_mm(self, k: int, member: str) -> float:
        st = self.stages[k]
        return st[member]["teeth"] * st["normal_module_mm"] / (2 * math.cos(self.beta(k)))

    def ratio(self, k: int) -> float:
        return self.stages[k]["gear"]["teeth"] / self.stages[k]["pinion"]["teeth"]

    @property
    def total_ratio(self) -> float:
        return math.prod(self.ratio(k) for k in range(len(self.stages)))

    @property
    def speed_ratios(self) -> list[float]:
        """rho_i = w_i / w_1 for every shaft."""
        out = [1.0]
        for k in range(len(self.stages)):
            out.append(out[-1] / self.ratio(k))
        return out

    # ------------------------------------------------------------------------------ loads
    @property
    def load_Nm(self) -> float:
        ld = self.doc["load"]
        return ld["torque_Nm"] if "torque_Nm" in ld else ld["torque_Nmm"] / 1e3

    @property
    def input_speed_rad_s(self) -> float:
        inp = self.doc["input"]
        if "speed_rad_s" in inp:
            return float(inp["speed_rad_s"])
        if "speed_rpm" in inp:
            return inp["speed_rpm"] * 2 * math.pi / 60
        return math.radians(inp["speed_deg_s"])

    def static_tangential_N(self, k: int) -> float:
        """F_t,k on the pitch circle at full load (signed like the load)."""
        downstream = math.prod(self.ratio(j) for j in range(k + 1, len(self.stages)))
        return self.load_Nm * 1e3 / downstream / self.pitch_radius_mm(k, "gear")

    def static_normal_N(self, k: int) -> float:
        return self.static_tangential_N(k) / (math.cos(self.alpha_n(k)) * math.cos(self.beta(k)))

    # ------------------------------------------------------------------------- contact law
    def law(self, k: int) -> dict:
        law = {"stiffness": "hertz", "exponent": 1.5, "damping_Ns_mm": 50.0, "full_damping_penetration_mm": 0.1}
        law.update(self.doc.get("contact", {}))
        law.update(self.stages[k].get("mesh", {}))
        return law

    def material(self, name: str) -> dict:
        return self.doc.get("materials", {}).get(name, SEED_MATERIAL)

    def hertz_K(self, k: int) -> float:
        """K = 4/3 sqrt(R) E*, N/mm^1.5."""
        st = self.stages[k]
        r1, r2 = self.pitch_radius_mm(k, "pinion"), self.pitch_radius_mm(k, "gear")
        R = r1 * r2 / (r1 + r2)
        inv_e = sum((1 - m["poisson_ratio"] ** 2) / m["youngs_modulus_MPa"]
                    for m in (self.material(st[g].get("material", "steel")) for g in ("pinion", "gear")))
        return 4.0 / 3.0 * math.sqrt(R) / inv_e

    def K(self, k: int) -> float:
        """The mesh constant in N/mm^e (a number in the file, or Hertz)."""
        s = self.law(k)["stiffness"]
        if s == "hertz":
            return self.hertz_K(k)
        if isinstance(s, (int, float)):
            return float(s)
        raise ValueError(f"stage {k + 1}: the catalogue has no hand calculation for stiffness = {s!r}")

    def static_approach_mm(self, k: int) -> float:
        """h_0 = (|F_n| / K)^(1/e), beyond the backlash half-gap."""
        return (abs(self.static_normal_N(k)) / self.K(k)) ** (1.0 / self.law(k)["exponent"])

    def potential_J(self, k: int, penetration_mm: np.ndarray) -> np.ndarray:
        e = self.law(k)["exponent"]
        return self.K(k) * np.abs(penetration_mm) ** (e + 1) / (e + 1) / 1e3  # N mm -> J

    # ----------------------------------------------------------------------------- inertia
    def gear_inertia(self, k: int, member: str) -> float:
        g = self.stages[k][member]
        if "inertia_kg_m2" in g:
            return float(g["inertia_kg_m2"])
        r = self.pitch_radius_mm(k, member) / 1e3
        rho = self.material(g.get("material", "steel"))["density_kg_m3"]
        return math.pi * rho * (g["face_width_mm"] / 1e3) * r**4 / 2

    @property
    def shaft_inertias(self) -> list[float]:
        n = len(self.stages)
        out = [self.gear_inertia(0, "pinion")]
        for k in range(n):
            out.append(self.gear_inertia(k, "gear") + (self.gear_inertia(k + 1, "pinion") if k + 1 < n else 0.0))
        return out

    @property
    def reflected_inertia(self) -> float:
        """J_eff = sum J_i rho_i^2, referred to the input shaft."""
        return sum(j * r * r for j, r in zip(self.shaft_inertias, self.speed_ratios, strict=True))

    # ------------------------------------------------------------------------- rigid motion
    def input_motion(self, t) -> tuple[np.ndarray, np.ndarray]:
        """w_1(t), alpha_1(t) of the STEP-ramped speed drive."""
        return step(t, self.doc["input"].get("ramp_s", 0.0), self.input_speed_rad_s)

    def load_torque_Nm(self, t) -> np.ndarray:
        return step(t, self.doc["load"].get("ramp_s", 0.0), self.load_Nm)[0]

    def rigid_tangential_N(self, k: int, t) -> np.ndarray:
        """F_t,k(t) of the rigid train under the speed drive (inertia of everything after gear k plus the load)."""
        rho, J = self.speed_ratios, self.shaft_inertias
        _, alpha1 = self.input_motion(t)
        downstream = sum(J[i] * rho[i] ** 2 for i in range(k + 1, len(J)))
        torque = (downstream * alpha1 + self.load_torque_Nm(t) * rho[-1]) / rho[k + 1]
        return torque * 1e3 / self.pitch_radius_mm(k, "gear")

    def rigid_kinetic_J(self, t) -> np.ndarray:
        return 0.5 * self.reflected_inertia * self.input_motion(t)[0] ** 2

    def rigid_load_work_J(self, t_end: float, n: int = 200_001) -> float:
        """int_0^t_end T_L(t) w_n(t) dt of the rigid train (fine trapezoid on the smooth STEP products)."""
        t = np.linspace(0.0, t_end, n)
        return float(np.trapezoid(self.load_torque_Nm(t) * self.input_motion(t)[0] * self.speed_ratios[-1], t))
