"""A test-only rating standard, complete in this one module: nominal stresses against the material's fatigue limits.

The proof of the rating seam (issue 34, plug-in seams): registered here and selected by
``[rating] standard = "nominal_stress"``, it flows through the design, the facade's simulated-K_v rating, life
(its own S–N curves) and the output with no other file changed. Deliberately simple, and closed form:

- contact stress σ_H = Z sqrt(K_v F_t / (b d_1) (u + 1) / u), Z = 475 √MPa (Z_E Z_H of a steel pair at 20°);
- root stress σ_F = Y K_v F_t / (b m_n), Y = 4.5 (Y_F Y_S of a mid-size tooth);
- the same nominal stress on both members; F_t the stage's static tangential force, b its face width, d_1 the
  pinion's reference diameter, u = z_gear / z_pinion;
- limits: the material's ``contact_fatigue_limit_MPa`` and 2 ``bending_fatigue_limit_MPa``; safety = limit / stress;
- S–N curve: a Basquin line from (N_static, f_static) to the knee (N_knee, 1), flat beyond (no damage below).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

from gearcli.errors import DesignError
from gearcli.rating import register
from gearcli.rating.dynamic import stage_simulated_k_v
from gearcli.rating.sn import SNCurve

Z = 475.0  # √MPa
Y = 4.5
CURVES = {"pitting": ((1e5, 1.6), (5e7, 1.0), (1e10, 1.0)), "bending": ((1e4, 2.5), (3e6, 1.0), (1e10, 1.0))}
TITLE = "nominal stress (a test standard)"


@dataclass(frozen=True)
class NominalMember:
    load_cycles: float
    sigma_H_MPa: float
    sigma_F_MPa: float
    limit_H_MPa: float
    limit_F_MPa: float
    S_H: float
    S_F: float

    def safety(self, mode: str) -> float:
        return self.S_H if mode == "pitting" else self.S_F

    def stress_MPa(self, mode: str) -> float:
        return self.sigma_H_MPa if mode == "pitting" else self.sigma_F_MPa


@dataclass(frozen=True)
class NominalRating:
    standard: str
    K_v: float
    K_v_source: str
    Z: float
    Y: float
    pinion: NominalMember
    gear: NominalMember

    def factor_table(self) -> dict[str, float | str]:
        return {"K_v": self.K_v, "K_v_source": self.K_v_source, "Z": self.Z, "Y": self.Y}


def stresses(f_t: float, b: float, d1: float, m_n: float, u: float, k_v: float) -> tuple[float, float]:
    """(σ_H, σ_F) of the standard's formulas."""
    return Z * math.sqrt(k_v * f_t / (b * d1) * (u + 1.0) / u), Y * k_v * f_t / (b * m_n)


def _rate(cfg, k: int, st, k_v: float, source: str) -> NominalRating:
    stage, life_h = cfg.stage[k], cfg.rating.required_life_h
    sigma_h, sigma_f = stresses(abs(st.static_force_N.tangential), st.face_width_mm, st.pinion.pitch_diameter_mm,
                                st.normal_module_mm, st.gear.teeth / st.pinion.teeth, k_v)
    members = []
    for part in ("pinion", "gear"):
        mat = cfg.materials[getattr(stage, part).material]
        lim_h, lim_f = float(mat.contact_fatigue_limit_MPa), 2.0 * float(mat.bending_fatigue_limit_MPa)
        members.append(NominalMember(60.0 * abs(getattr(st, part).speed_rpm) * life_h, sigma_h, sigma_f, lim_h, lim_f,
                                     lim_h / sigma_h, lim_f / sigma_f))
    return NominalRating(TITLE, k_v, source, Z, Y, *members)


class NominalStress:
    name = "nominal_stress"
    title = TITLE

    def check_inputs(self, cfg) -> None:
        for stage in cfg.stage:
            for part in ("pinion", "gear"):
                name = getattr(stage, part).material
                mat = cfg.materials.get(name)
                for key in ("contact_fatigue_limit_MPa", "bending_fatigue_limit_MPa"):
                    if mat is not None and getattr(mat, key) is None:
                        raise DesignError(f"the nominal-stress rating needs {key}", key=f"materials.{name}.{key}")

    def _k_v(self, cfg) -> tuple[float, str]:
        given = cfg.rating.dynamic_factor
        return (given, "given") if isinstance(given, float) else (1.0, "nominal")

    def rate_design(self, cfg, stages):
        k_v, source = self._k_v(cfg)
        return tuple(replace(st, rating=_rate(cfg, k, st, k_v, source)) for k, st in enumerate(stages)), ()

    def rate_simulation(self, cfg, design, stages):
        if cfg.rating.dynamic_factor != "simulated":
            return tuple(stages), []
        return tuple(replace(sd, rating=_rate(cfg, k, design.stages[k], stage_simulated_k_v(sd), "simulated"))
                     for k, sd in enumerate(stages)), []

    def sn_curve(self, cfg, member, treatment, mode, variant) -> SNCurve:
        limit = member.limit_H_MPa if mode == "pitting" else member.limit_F_MPa
        return SNCurve(CURVES[mode], limit, variant, optimum=True)

    def curve_name(self, mode: str) -> str:
        return f"nominal {mode} Basquin line (test)"

    def table_rows(self, ratings, *, shared: bool) -> list[tuple[str, list[str]]]:
        rows = [(name, [f"{r.factor_table()[name]}" for r in ratings]) for name in ("K_v", "K_v_source", "Z", "Y")]
        for mode in ("pitting", "bending"):
            rows.append((f"{mode} safety p / g", [f"{r.pinion.safety(mode):.4g} / {r.gear.safety(mode):.4g}"
                                                  for r in ratings]))
        return rows


NOMINAL_STRESS = register(NominalStress())
