"""The load factors of one mesh, ISO 6336-1:2006 (method B): the one K_v / K_Hβ resolution of every rated mesh, a gear
pair's (``rating``) and a planetary stage's planet–ring mesh (``rating_internal``) alike (docs/iso6336.md).

K_v: the run's (``simulated_k_v``, ``"simulated"``), else ``[rating] dynamic_factor`` as a number (``"given"``), else
ISO 6336-1 method B from the mesh's resonance ratio (``"iso"``). K_Hβ: ``[rating] face_load_factor`` (``"given"``),
else the estimate from c_γβ and the helix slope deviation of the grade (``"estimated"``). Both from the deviations of
the ISO 1328-1 grade less running-in; K_Fβ, K_Hα, K_Fα and Z_ε follow.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from gearcli.core.records import record
from gearcli.design import rating_factors as rf

if TYPE_CHECKING:
    from gearcli.config.schema import Rating


@record
class MeshLoad:
    """What ISO 6336-1's load factors read of a mesh; index ``small`` of the pairs is ISO's pinion (index 1)."""

    grade: int  # ISO 1328-1 accuracy grade
    normal_module_mm: float
    transverse_pressure_angle_rad: float  # α_t
    pitch_diameters_mm: tuple[float, float]
    treatments: tuple[str, str]
    hlim_MPa: tuple[float, float]  # σ_Hlim
    small: int
    speed_m_s: float  # pitch-line speed (of the carrier frame for a planetary stage's meshes)
    line_load_N_mm: float  # F_t K_A / b
    face_width_mm: float
    resonance_ratio: float  # N = n1 / n_E1
    resonance_lower_limit: float  # N_S
    contact_ratios: tuple[float, float, float]  # ε_α, ε_β, ε_γ
    single_pair_stiffness: float  # c′ [N/(mm·µm)]
    mesh_stiffness: float  # c_γα
    mesh_stiffness_beta: float  # c_γβ
    tip_relief_um: float  # C_a
    tooth_depth_mm: float  # h of K_Fβ's b/h


@record
class LoadFactors:
    k_v: float
    k_v_source: str  # "simulated" | "given" | "iso"
    k_hb: float
    k_hb_source: str  # "given" | "estimated"
    k_fb: float
    k_ha: float
    k_fa: float
    z_eps: float


def resolve_load_factors(rating: Rating, m: MeshLoad, simulated_k_v: float | None = None) -> LoadFactors:
    """ISO 6336-1: deviations of the grade, running-in, K_v, K_Hβ, K_Fβ, K_Hα, K_Fα, and Z_ε (K_Hα's limit)."""
    f_pb = max(rf.single_pitch_tolerance_um(d, m.normal_module_mm, m.grade)
               for d in m.pitch_diameters_mm) * math.cos(m.transverse_pressure_angle_rad)
    f_fa = max(rf.profile_form_tolerance_um(d, m.normal_module_mm, m.grade) for d in m.pitch_diameters_mm)
    pairs = tuple(zip(m.treatments, m.hlim_MPa, strict=True))
    y_a = 0.5 * sum(rf.running_in_um(t, h, f_pb, m.speed_m_s) for t, h in pairs)
    y_f = 0.5 * sum(rf.running_in_um(t, h, f_fa, m.speed_m_s) for t, h in pairs)
    eps_a, eps_b, eps_g = m.contact_ratios
    line_load, b, d1 = m.line_load_N_mm, m.face_width_mm, m.pitch_diameters_mm[m.small]
    if simulated_k_v is not None:
        k_v, k_v_source = max(1.0, simulated_k_v), "simulated"
    elif isinstance(rating.dynamic_factor, float):
        k_v, k_v_source = rating.dynamic_factor, "given"
    else:  # C_a = tip_relief_um; running-in is in f_pb,eff and f_fα,eff, not in B_k
        k_v = rf.dynamic_factor(m.resonance_ratio, m.resonance_lower_limit, eps_g, m.single_pair_stiffness,
                                line_load, f_pb - y_a, f_fa - y_f, m.tip_relief_um)
        k_v_source = "iso"
    if rating.face_load_factor is not None:
        k_hb, k_hb_source = rating.face_load_factor, "given"
    else:
        f_hb = rf.helix_slope_tolerance_um(d1, b, m.grade)
        k_hb = rf.face_load_factor_estimate(m.mesh_stiffness_beta, line_load * k_v, f_hb, b / d1,
                                            (pairs[0], pairs[1], m.speed_m_s))
        k_hb_source = "estimated"
    z_eps = rf.contact_ratio_factor(eps_a, eps_b)
    k_ha, k_fa = rf.transverse_load_factors(eps_a, eps_g, z_eps, m.mesh_stiffness, max(f_pb, f_fa) - y_a,
                                            line_load * k_v * k_hb)
    return LoadFactors(k_v, k_v_source, k_hb, k_hb_source, rf.face_load_factor_root(k_hb, b, m.tooth_depth_mm),
                       k_ha, k_fa, z_eps)
