"""Shaft statics: every shaft on its two bearings under the tooth forces of its gears (docs/physics.md,
"Shaft statics and bearings"); ISO 281 basic rating life of each bearing.

The frame: x runs along every shaft away from the input end (axial positions are measured along x from one
housing plane); "cw" is a positive rotation about +x (clockwise seen from the input end looking along +x);
a stage's ``center_angle_deg`` phi turns the line of centres, pinion axis to gear axis, from the housing's
reference direction y the same way, u = (0, cos phi, sin phi); z completes the right-handed frame.

Tooth forces at the operating (working) pitch point P, on the line of centres at r_w1 from the pinion axis,
from the transverse line-of-action force F_bt = T_1 / r_b1 (signed: positive while the pinion drives):
F_t = F_bt cos a_wt, F_r = |F_bt| sin a_wt (always separating the wheels), F_a = F_bt tan b_b (= F_t tan b_w).
With t = x X u the direction the pinion's surface at P moves when it turns positively, s_p = +1/-1 its
sense of rotation and h_p = +1/-1/0 its hand (right/left/spur):
    on the pinion   F = -s_p F_t t - F_r u + s_p h_p F_a x
    on the gear     F = +s_p F_t t + F_r u - s_p h_p F_a x
applied at P, so the axial force's moment about the shaft axis (arm r_w) comes from the point of application.
Pure ``math``: the design layer never imports numpy or scipy.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

from gearcli.errors import DesignError
from gearcli.results import BearingResult

if TYPE_CHECKING:
    from gearcli.config.schema import DesignFile
    from gearcli.results import StageResult

Vec = tuple[float, float, float]
BALL_EXPONENT = 3.0  # ISO 281: p = 3 for ball bearings
ROLLER_EXPONENT = 10.0 / 3.0  # p = 10/3 for roller bearings


def life_exponent(kind: str) -> float:
    """ISO 281 life exponent p: 3 for ball, 10/3 for roller bearings."""
    return BALL_EXPONENT if kind == "ball" else ROLLER_EXPONENT


def equivalent_load_N(radial_N: float, axial_N: float, e: float, X: float, Y: float) -> float:
    """ISO 281 dynamic equivalent load: P = F_r when F_a / F_r <= e, else X F_r + Y F_a (magnitudes)."""
    fr, fa = abs(radial_N), abs(axial_N)
    if fa <= e * fr:
        return fr
    return X * fr + Y * fa


def basic_life_Mrev(rating_N: float, load_N: float, kind: str) -> float | None:
    """ISO 281 basic rating life L10 = (C / P)^p in millions of revolutions; None for an unloaded bearing."""
    if load_N <= 0.0:
        return None
    return (rating_N / load_N) ** life_exponent(kind)


def life_hours(life_Mrev: float | None, speed_rpm: float) -> float | None:
    """L10h = 1e6 L10 / (60 n); None when the life is unbounded or the shaft stands still."""
    if life_Mrev is None or speed_rpm == 0.0:
        return None
    return 1e6 * life_Mrev / (60.0 * abs(speed_rpm))


def spectrum_equivalent_load_N(loads_N: Sequence[float], revolutions: Sequence[float], kind: str) -> float:
    """ISO 281 equivalent load over a duty spectrum: P = (sum P_i^p N_i / sum N_i)^(1/p), N_i the revolutions
    at level i (speed x time); the same life as Miner's sum of the levels' L10."""
    p = life_exponent(kind)
    total = sum(revolutions)
    if total <= 0.0:
        return 0.0
    return (sum(abs(f) ** p * n for f, n in zip(loads_N, revolutions, strict=True)) / total) ** (1.0 / p)


# ----------------------------------------------------------------------------------------- statics
def cross(a: Vec, b: Vec) -> Vec:
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


@dataclass(frozen=True)
class PointLoad:
    """A force (N) on a shaft at a point (mm): x along the shaft, y and z off its axis."""

    point_mm: Vec
    force_N: Vec


@dataclass(frozen=True)
class Reaction:
    """What a bearing exerts on its shaft (N): radial components in y and z, axial along x."""

    y_N: float
    z_N: float
    axial_N: float

    @property
    def radial_N(self) -> float:
        return math.hypot(self.y_N, self.z_N)


def shaft_reactions(loads: Sequence[PointLoad], x_a_mm: float, x_b_mm: float,
                    locating_a: bool) -> tuple[Reaction, Reaction]:
    """Reactions of bearings A and B (radial supports on the axis at x_a, x_b; the locating one also takes
    the axial force) that hold the shaft in equilibrium: sum of forces and of bending moments about A vanish
    (the moment about x, the torque, is balanced by the shaft's other gear or coupling)."""
    span = x_b_mm - x_a_mm
    fx = sum(ld.force_N[0] for ld in loads)
    fy = sum(ld.force_N[1] for ld in loads)
    fz = sum(ld.force_N[2] for ld in loads)
    my = mz = 0.0
    for ld in loads:
        arm = (ld.point_mm[0] - x_a_mm, ld.point_mm[1], ld.point_mm[2])
        m = cross(arm, ld.force_N)
        my += m[1]
        mz += m[2]
    # R_B at (span, 0, 0) from A: its moment is span x X R_B = (0, -span R_Bz, span R_By)
    rb_y, rb_z = -mz / span, my / span
    ra_y, ra_z = -fy - rb_y, -fz - rb_z
    return (Reaction(ra_y, ra_z, -fx if locating_a else 0.0), Reaction(rb_y, rb_z, 0.0 if locating_a else -fx))


@dataclass(frozen=True)
class MeshLayout:
    """What the statics needs of one stage, independent of the load."""

    stage: int  # 0-based
    line_of_centres: Vec  # u
    tangent: Vec  # t = x X u
    pinion_sense: int  # s_p: +1 turns positively about +x, -1 negatively
    pinion_hand: int  # h_p: +1 right, -1 left, 0 spur
    working_pressure_rad: float
    base_helix_rad: float
    working_radius_mm: tuple[float, float]  # pinion, gear
    axial_position_mm: tuple[float | None, float | None]  # pinion, gear


def mesh_loads(m: MeshLayout, line_force_N: float) -> tuple[PointLoad, PointLoad]:
    """The tooth forces on pinion and gear (at P) for the transverse line-of-action force F_bt (signed)."""
    f_t = line_force_N * math.cos(m.working_pressure_rad)
    f_r = abs(line_force_N) * math.sin(m.working_pressure_rad)
    f_a = line_force_N * math.tan(m.base_helix_rad)
    s, h, u, t = m.pinion_sense, m.pinion_hand, m.line_of_centres, m.tangent
    on_pinion = tuple(-s * f_t * t[i] - f_r * u[i] for i in range(3))
    on_pinion = (on_pinion[0] + s * h * f_a, on_pinion[1], on_pinion[2])
    on_gear = (-on_pinion[0], -on_pinion[1], -on_pinion[2])
    rp, rg = m.working_radius_mm
    xp, xg = (x or 0.0 for x in m.axial_position_mm)
    return (PointLoad((xp, rp * u[1], rp * u[2]), on_pinion),
            PointLoad((xg, -rg * u[1], -rg * u[2]), on_gear))


@dataclass(frozen=True)
class BearingSpec:
    index: int  # 0-based position in [[bearing]]
    shaft: int  # 1-based
    position_mm: float
    rating_N: float
    kind: str
    locating: bool
    e: float
    X: float
    Y: float


@dataclass(frozen=True)
class ShaftLayout:
    """The supported shafts of a design: which mesh loads act on which shaft, and its two bearings."""

    meshes: tuple[MeshLayout, ...]
    shafts: dict[int, tuple[BearingSpec, BearingSpec]]  # 1-based shaft -> (A, B)

    def loads_on(self, shaft: int, line_forces_N: Sequence[float]) -> list[PointLoad]:
        """Shaft j (1-based) carries pinion j (stage j-1, 0-based) and gear j-1 (stage j-2)."""
        out: list[PointLoad] = []
        for m in self.meshes:
            if m.stage + 1 == shaft or m.stage + 2 == shaft:
                pl, gl = mesh_loads(m, line_forces_N[m.stage])
                out.append(pl if m.stage + 1 == shaft else gl)
        return out

    def reactions(self, line_forces_N: Sequence[float]) -> list[tuple[BearingSpec, Reaction]]:
        """Every bearing's reaction, in [[bearing]] order, for the stages' line-of-action forces F_bt."""
        found: list[tuple[BearingSpec, Reaction]] = []
        for shaft, (a, b) in self.shafts.items():
            ra, rb = shaft_reactions(self.loads_on(shaft, line_forces_N), a.position_mm, b.position_mm, a.locating)
            found += [(a, ra), (b, rb)]
        return sorted(found, key=lambda pair: pair[0].index)


def layout(cfg: DesignFile, working_radii_mm: Sequence[tuple[float, float]],
           working_pressure_rad: Sequence[float], base_helix_rad: Sequence[float]) -> ShaftLayout | None:
    """The shaft layout of a design file with ``[[bearing]]`` tables (None without). Raises DesignError
    naming the key for a bearing on a shaft that does not exist, a shaft without exactly two bearings or
    one locating bearing, two bearings at one position, or a gear on a supported shaft without
    ``axial_position_mm``."""
    if not cfg.bearing:
        return None
    n_shafts = len(cfg.stage) + 1
    by_shaft: dict[int, list[BearingSpec]] = {}
    for j, b in enumerate(cfg.bearing):
        if b.shaft > n_shafts:
            raise DesignError(f"shaft {b.shaft} does not exist: this train has shafts 1 to {n_shafts} (1 = the input "
                              "shaft, k+1 = gear k with pinion k+1)", key=f"bearing[{j}].shaft")
        by_shaft.setdefault(b.shaft, []).append(BearingSpec(j, b.shaft, b.position_mm, b.dynamic_load_rating_kN * 1e3,
                                                            b.kind, b.locating, b.factors.e, b.factors.X, b.factors.Y))
    shafts = {s: _pair(s, specs) for s, specs in sorted(by_shaft.items())}
    sense = 1 if cfg.input.rotation == "cw" else -1
    meshes = []
    for k in range(len(cfg.stage)):
        if getattr(cfg.stage[k], "type", "parallel") == "planetary":
            raise DesignError("the shaft statics of a planetary stage are not modelled: [[bearing]] tables need a "
                              "train of parallel stages", key=f"stage[{k}].type")
        stage = cfg.pair(k)
        phi = math.radians(stage.center_angle_deg)
        u = (0.0, math.cos(phi), math.sin(phi))
        hand = {"right": 1, "left": -1}.get(stage.pinion.hand or "spur", 0) if stage.helix_angle_deg > 0 else 0
        positions = (stage.pinion.axial_position_mm, stage.gear.axial_position_mm)
        for member, shaft, pos in (("pinion", k + 1, positions[0]), ("gear", k + 2, positions[1])):
            if shaft in shafts and pos is None:
                raise DesignError(f"shaft {shaft} has bearings, so its {member} needs its axial position (the gear "
                                  "centre along x from the housing plane)", key=f"stage[{k}].{member}.axial_position_mm")
        meshes.append(MeshLayout(k, u, cross((1.0, 0.0, 0.0), u), sense * (-1) ** k, hand, working_pressure_rad[k],
                                 base_helix_rad[k], tuple(working_radii_mm[k]), positions))  # type: ignore[arg-type]
    return ShaftLayout(tuple(meshes), shafts)


def _pair(shaft: int, specs: list[BearingSpec]) -> tuple[BearingSpec, BearingSpec]:
    first = f"bearing[{specs[0].index}]"
    if len(specs) != 2:
        raise DesignError(f"shaft {shaft} has {len(specs)} bearing(s): a shaft rests on exactly two (one locating, "
                          "one floating)", key=f"{first}.shaft")
    locating = [s for s in specs if s.locating]
    if len(locating) != 1:
        raise DesignError(f"shaft {shaft} has {len(locating)} locating bearings: exactly one of its two bearings "
                          "takes the axial force (locating = true)", key=f"{first}.locating")
    if specs[0].position_mm == specs[1].position_mm:
        raise DesignError(f"the two bearings of shaft {shaft} sit at the same position_mm: the shaft needs a span",
                          key=f"bearing[{specs[1].index}].position_mm")
    a, b = sorted(specs, key=lambda s: s.position_mm)
    return a, b


# ------------------------------------------------------------------------------------ design results
def stage_layout(cfg: DesignFile, stages: Sequence[StageResult]) -> ShaftLayout | None:
    """The shaft layout from the design's stage geometry (working pitch radii r_w = r_b / cos a_wt)."""
    alphas = [math.radians(s.working_pressure_angle_deg) for s in stages]
    radii = [(0.5 * s.pinion.base_diameter_mm / math.cos(a), 0.5 * s.gear.base_diameter_mm / math.cos(a))
             for s, a in zip(stages, alphas, strict=True)]
    return layout(cfg, radii, alphas, [math.radians(s.base_helix_angle_deg) for s in stages])


def line_forces_N(stages: Sequence[StageResult]) -> list[float]:
    """F_bt = T_1 / r_b1 per stage from the pinion torques (N·mm / mm)."""
    return [s.pinion.torque_Nmm / (0.5 * s.pinion.base_diameter_mm) for s in stages]


def bearing_results(cfg: DesignFile, stages: Sequence[StageResult],
                    shaft_speeds_rpm: Sequence[float]) -> tuple[BearingResult, ...]:
    """Static reactions and ISO 281 lives of every ``[[bearing]]`` at the design's load (empty without)."""
    lay = stage_layout(cfg, stages)
    if lay is None:
        return ()
    return tuple(bearing_result(spec, r, shaft_speeds_rpm[spec.shaft - 1])
                 for spec, r in lay.reactions(line_forces_N(stages)))


def bearing_result(spec: BearingSpec, r: Reaction, speed_rpm: float) -> BearingResult:
    p = equivalent_load_N(r.radial_N, r.axial_N, spec.e, spec.X, spec.Y)
    l10 = basic_life_Mrev(spec.rating_N, p, spec.kind)
    return BearingResult(shaft=spec.shaft, position_mm=spec.position_mm, radial_N=r.radial_N, radial_y_N=r.y_N,
                         radial_z_N=r.z_N, axial_N=r.axial_N, equivalent_load_N=p, L10_Mrev=l10,
                         L10_h=life_hours(l10, speed_rpm), kind=spec.kind, locating=spec.locating,
                         dynamic_load_rating_kN=spec.rating_N / 1e3, speed_rpm=abs(speed_rpm))
