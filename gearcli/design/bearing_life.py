"""A bearing's ISO 281 modified life and ISO 76 static safety from its design-file keys (docs/bearings.md).

:func:`check_inputs` refuses an incomplete set (exit 2 naming the key); :func:`lubrication` reads the oil at its
operating temperature; :func:`static_figures` and :func:`modified_figures` give the new figures of one bearing
at one load; :func:`static_warning` warns below the minimum s_0. The life side (``gearcli.life``) combines the
figures of the duty points and starts through :func:`duty_modified_life` and :func:`min_static_safety`.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Protocol

from gearcli.core.text import beside, rounded_up
from gearcli.design import iso281
from gearcli.diagnostics import BEARING_LIFE_SHORT, Diagnostic, warning
from gearcli.errors import DesignError

if TYPE_CHECKING:
    from gearcli.config.schema import DesignFile
    from gearcli.optional_results import BearingResult

STATIC_SAFETY_LOW = "bearing_static_safety_low"
KAPPA_OUT_OF_RANGE = "bearing_kappa_below_range"
AXIAL_NOT_RATED = "bearing_axial_not_rated"
MODIFIED_KEYS = ("fatigue_load_limit_kN", "pitch_diameter_mm", "reliability_percent")


class RatedBearing(Protocol):
    """What a life verdict reads of a bearing: design's BearingResult, life's BearingLife."""

    @property
    def shaft(self) -> int: ...
    @property
    def position_mm(self) -> float: ...
    @property
    def planet_stage(self) -> int | None: ...
    @property
    def equivalent_load_N(self) -> float: ...
    @property
    def dynamic_load_rating_kN(self) -> float: ...
    @property
    def L10_h(self) -> float | None: ...
    @property
    def L_nm_h(self) -> float | None: ...
    @property
    def kind(self) -> str: ...


def wants_modified_life(cfg: DesignFile, j: int) -> bool:
    b = cfg.bearing[j]
    return any(getattr(b, k) is not None for k in MODIFIED_KEYS)


def check_inputs(cfg: DesignFile) -> None:
    """Every bearing that asks for its modified life (any of C_u, d_m, reliability) has C_u and d_m, and the
    [lubricant] table has the oil and its cleanliness; DesignError naming the missing key otherwise."""
    for j, b in enumerate(cfg.bearing):
        if "static_factors" in b.model_fields_set and b.static_load_rating_kN is None:
            raise DesignError("static_factors set the ISO 76 static equivalent load, whose safety needs the static "
                              "load rating C_0", key=f"bearing[{j}].static_load_rating_kN")
    asking = [j for j in range(len(cfg.bearing)) if wants_modified_life(cfg, j)]
    for j in asking:
        for key in ("fatigue_load_limit_kN", "pitch_diameter_mm"):
            if getattr(cfg.bearing[j], key) is None:
                raise DesignError("the ISO 281 modified life needs the fatigue load limit C_u and the pitch diameter "
                                  "d_m = (d + D)/2 of the bearing (catalogue values)", key=f"bearing[{j}].{key}")
    if not asking:
        return
    why = f"bearing[{asking[0]}] asks for its ISO 281 modified life, which needs "
    lub = cfg.lubricant
    if lub is None or lub.viscosity_40C_mm2_s is None:
        raise DesignError(why + "the oil's viscosity (and its operating temperature)",
                          key="lubricant.viscosity_40C_mm2_s")
    if lub.temperature_C is None:
        raise DesignError(why + "the oil's operating temperature (kappa = nu / nu_1 at it)", key="lubricant.temperature_C")
    if lub.temperature_C != 40.0 and lub.viscosity_100C_mm2_s is None:
        raise DesignError(why + f"the oil's viscosity at {lub.temperature_C:g} °C: give its 100 °C value too "
                          "(ASTM D341 through the 40 °C and 100 °C values)", key="lubricant.viscosity_100C_mm2_s")
    if lub.contamination is None and lub.e_C is None:
        raise DesignError(why + "the lubricant's cleanliness: an ISO 281 level (extreme, high, normal, slight, "
                          "typical, severe, very_severe) or e_C", key="lubricant.contamination")


def lubrication(cfg: DesignFile) -> iso281.Lubrication | None:
    """The oil at its operating temperature and its cleanliness (None without what a_ISO needs)."""
    lub = cfg.lubricant
    if (lub is None or lub.viscosity_40C_mm2_s is None or lub.temperature_C is None
            or (lub.contamination is None and lub.e_C is None)):
        return None
    nu = iso281.viscosity_at_mm2_s(lub.temperature_C, lub.viscosity_40C_mm2_s, lub.viscosity_100C_mm2_s)
    return iso281.Lubrication(nu, lub.contamination, lub.e_C)


def min_static_safety_required(cfg: DesignFile, kind: str) -> float:
    """``[rating] min_static_safety_bearing`` (with or without a gear rating) or the guideline for the bearing kind
    (iso281.MIN_STATIC_SAFETY)."""
    given = cfg.min_static_safety_bearing
    return given if given is not None else iso281.MIN_STATIC_SAFETY[kind]


def static_figures(static_rating_N: float | None, X0: float, Y0: float, radial_N: float, axial_N: float
                   ) -> tuple[float | None, float | None]:
    """(P_0, s_0) at one load; (None, None) without C_0."""
    if static_rating_N is None:
        return None, None
    p0 = iso281.static_equivalent_load_N(radial_N, axial_N, X0, Y0)
    return p0, iso281.static_safety(static_rating_N, p0)


def min_static_safety(static_rating_N: float, peak_loads_N: Sequence[float]) -> tuple[float, float | None]:
    """(largest P_0, smallest s_0) over a list of peak static equivalent loads: the duty points' and, once the
    duty has starts, every start's peaks (``gearcli.life.run.start_bearings``)."""
    p0 = max(peak_loads_N, default=0.0)
    return p0, iso281.static_safety(static_rating_N, p0)


def static_warning(cfg: DesignFile, j: int, kind: str, s0: float | None, where: str) -> Diagnostic | None:
    """A warning when bearing j's s_0 is below the minimum (``where``: "at the static load", ...)."""
    needed = min_static_safety_required(cfg, kind)
    if s0 is None or s0 >= needed:
        return None
    return warning(STATIC_SAFETY_LOW, f"bearing {j + 1}: static safety s_0 = C_0/P_0 = {beside(s0, needed)} {where} is below the "
                   f"minimum {needed:.3g} (ISO 76; [rating] min_static_safety_bearing); choose a bearing with a "
                   "larger C_0", bearing=j + 1, s0=s0, s0_min=needed)


def kappa_warning(j: int, kappa: float, where: str = "", points: Sequence[str] | None = None) -> Diagnostic | None:
    """A warning when bearing j's kappa is below ISO 281's range (``where``: " (the lowest over the duty; ...)",
    ...; ``points``: the duty points below it, in the data as ``points`` when given)."""
    if kappa >= iso281.KAPPA_MIN:
        return None
    extra = {} if points is None else {"points": list(points)}
    return warning(KAPPA_OUT_OF_RANGE, f"bearing {j + 1}: viscosity ratio kappa = {beside(kappa, iso281.KAPPA_MIN)}{where} is below 0.1, "
                   "where ISO 281's a_ISO does not apply; a_ISO is taken at kappa = 0.1", bearing=j + 1, kappa=kappa,
                   **extra)


def duty_modified_life(levels: Sequence[tuple[float, float | None, iso281.ModifiedLife]]
                       ) -> tuple[float | None, float | None]:
    """Palmgren–Miner over load levels (revolutions n_i, L10_i, its modified life): L_nm = sum n_i / sum (n_i /
    L_nm,i), and the duty's effective a_ISO = L_nm / (a_1 L10) with L10 over the same levels (None, 0 when no
    level damages the bearing)."""
    revs = sum(n for n, _, _ in levels)
    damage = sum(n / m.L_nm_Mrev for n, _, m in levels if m.L_nm_Mrev)
    basic = sum(n / l10 for n, l10, _ in levels if l10)
    if damage <= 0.0 or revs <= 0.0:
        return None, None
    l_nm = revs / damage
    a1 = levels[0][2].a_1
    return l_nm, l_nm / (a1 * revs / basic) if basic > 0.0 else None


def axial_warning(cfg: DesignFile, j: int, b: BearingResult) -> Diagnostic | None:
    """A warning when bearing j carries an axial force without ``factors``: its ISO 281 P = F_r by the default
    X = 1, Y = 0 ignores F_a (and, with C_0 and no ``static_factors``, so does ISO 76's P_0); with ``factors`` but
    C_0 and no ``static_factors``, that its P_0 ignores F_a. The message names
    F_a/F_r, not F_a; ``gearcli life`` says it once per bearing over the duty (a reversed point's F_a/F_r differs,
    its axial force's moment loading the other bearing)."""
    given = cfg.bearing[j].model_fields_set
    fa, fr = abs(b.axial_N), abs(b.radial_N)
    if fa <= 1e-9 * max(fr, 1.0):
        return None
    static = b.static_load_rating_kN is not None and "static_factors" not in given
    ratio = f"{fa / fr:.3g}" if fr > 0.0 else "inf"
    if "factors" in given:
        if not static:
            return None
        # the dynamic factors given, the static ones not: ISO 76's P_0 = F_r silently ignored F_a
        return warning(AXIAL_NOT_RATED, f"bearing {j + 1} carries an axial force (F_a/F_r = {ratio}) but has no "
                       "static_factors: its ISO 76 static equivalent load P_0 takes F_r alone (default X0 = 1, Y0 = 0), "
                       "so its static safety s_0 ignores F_a; give the catalogue's static_factors = { X0, Y0 }",
                       bearing=j + 1, axial_N=fa, radial_N=fr)
    return warning(AXIAL_NOT_RATED, f"bearing {j + 1} carries an axial force (F_a/F_r = {ratio}) "
                   f"but has no factors: its ISO 281 equivalent load P{' and ISO 76 P_0 take' if static else ' takes'} F_r "
                   "alone (default X = 1, Y = 0); give the catalogue's factors = { e, X, Y }"
                   + (" and static_factors = { X0, Y0 }" if static else ""), bearing=j + 1, axial_N=fa, radial_N=fr)


def bearing_diagnostics(cfg: DesignFile, bearings: Sequence[BearingResult]) -> list[Diagnostic]:
    """The design's bearing warnings: s_0 below its minimum at the static load, kappa below ISO 281's range (a
    loaded bearing's: an unloaded one has no a_ISO), an axial force the equivalent loads ignore, a life shorter
    than [rating] required_life_h."""
    out: list[Diagnostic] = []
    required_h = cfg.rating.required_life_h if cfg.rating is not None else None
    for j, b in enumerate(bearings):
        found = [static_warning(cfg, j, b.kind, b.static_safety, "at the static load"),
                 None if b.kappa is None or b.a_ISO is None else kappa_warning(j, b.kappa), axial_warning(cfg, j, b),
                 life_short_warning(j, b, "at the design load", None, required_h)]
        out += [d for d in found if d is not None]
    return out


def life_short_warning(j: int, b: RatedBearing, over: str, hours: float | None,
                       required_h: float | None) -> Diagnostic | None:
    """A warning when bearing j's ISO 281 life (L_nm where its catalogue data give it, else L10) is shorter than
    ``hours`` (the duty's, ``gearcli life``) or than ``required_h`` ([rating] required_life_h); ``over``: where the
    life is taken ("over the duty", "at the design load"). None for an unbounded life (an unloaded bearing)."""
    name, life = ("L_nm", b.L_nm_h) if b.L_nm_h is not None else ("L10", b.L10_h)
    short_of_duty = hours is not None and life is not None and life < hours
    if life is None or not (short_of_duty or (required_h is not None and life < required_h)):
        return None
    target = (f"the duty's {hours:.6g} h" if short_of_duty else
              f"the required {required_h:.6g} h ([rating] required_life_h)")
    place = f"planet pin of stage {b.planet_stage}" if b.planet_stage else f"shaft {b.shaft}"
    p = iso281.life_exponent(b.kind)
    needed = rounded_up(b.dynamic_load_rating_kN * (((hours if short_of_duty else required_h) or life) / life) ** (1 / p))
    return warning(BEARING_LIFE_SHORT, f"bearing {j + 1} ({place}, x = {b.position_mm:g} mm): its ISO 281 "
                   f"life {name} = {life:.4g} h {over} is shorter than {target} "
                   f"(equivalent load {b.equivalent_load_N:.5g} N, C = {b.dynamic_load_rating_kN:g} kN); a bearing of "
                   f"bearing[{j}].dynamic_load_rating_kN ≥ {needed:g} kN lasts it at the same loads (the life goes "
                   f"as C^{p:.3g}, p = {'3 for a ball' if b.kind == 'ball' else '10/3 for a roller'} bearing)",
                   bearing=j + 1, life=name, life_h=life, hours=hours, required_life_h=required_h,
                   required_dynamic_load_rating_kN=needed)

