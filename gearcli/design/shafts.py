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
from dataclasses import field, replace
from typing import TYPE_CHECKING, cast

from gearcli.core.records import record
from gearcli.design.bearing_life import check_inputs, lubrication, static_figures
from gearcli.design.iso281 import Lubrication, life_exponent, modified_life
from gearcli.design.planetary_balance import planet_angles_deg, willis_speeds
from gearcli.errors import DesignError
from gearcli.optional_results import BearingResult
from gearcli.stages.design import design_kind

if TYPE_CHECKING:
    from gearcli.config.schema import DesignFile, PlanetaryStage
    from gearcli.results import StageResult

Vec = tuple[float, float, float]

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


@record
class PointLoad:
    """A force (N) on a shaft at a point (mm): x along the shaft, y and z off its axis."""

    point_mm: Vec
    force_N: Vec


@record
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


@record
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


@record
class BearingSpec:
    index: int  # 0-based position in [[bearing]]
    shaft: int  # 1-based; 0 for a planet pin's bearing
    position_mm: float
    rating_N: float
    kind: str
    locating: bool
    e: float
    X: float
    Y: float
    planet_stage: int = 0  # a planet pin's bearing: its planetary stage, 1-based; 0 for a shaft's
    static_rating_N: float | None = None  # C_0 (ISO 76 static safety; docs/bearings.md)
    X0: float = 1.0
    Y0: float = 0.0
    fatigue_limit_N: float | None = None  # C_u (ISO 281 modified life)
    pitch_diameter_mm: float | None = None  # d_m
    reliability_percent: float = 90.0


def _spec(j: int, b, shaft: int, planet_stage: int = 0) -> BearingSpec:
    """Bearing j of the design file (``[[bearing]]`` table ``b``) on shaft ``shaft`` or a planet pin."""
    return BearingSpec(j, shaft, b.position_mm, b.dynamic_load_rating_kN * 1e3, b.kind, b.locating, b.factors.e,
                       b.factors.X, b.factors.Y, planet_stage,
                       None if b.static_load_rating_kN is None else b.static_load_rating_kN * 1e3,
                       b.static_factors.X0, b.static_factors.Y0,
                       None if b.fatigue_load_limit_kN is None else b.fatigue_load_limit_kN * 1e3,
                       b.pitch_diameter_mm, 90.0 if b.reliability_percent is None else b.reliability_percent)


@record
class PlanetaryLayout:
    """What the statics needs of one planetary stage (docs/life.md, "Planetary stages").

    The global frame of the module; planet j sits at psi_j about the central axis, r_j = (0, cos psi_j,
    sin psi_j) from the axis to its centre, t_j = x X r_j. The sun-mesh pitch point is at r_w,s r_j from the
    axis (r_w,p,s from the planet's centre towards the sun), the ring-mesh pitch point at r_w,r r_j (r_w,p,r
    beyond the planet's centre). Per planet and transverse line force F_bt of its sun mesh: the planet's moment
    balance about its own axis, F_bt,sp r_b,p = F_bt,rp r_b,p (both meshes act on the planet's one base
    cylinder), gives the ring mesh the same F_bt, so its tangential force at its own working circle is
    F_bt cos a_w,rp (not the sun mesh's F_bt cos a_w,sp: the two differ where the working pressure angles do,
    e.g. profile-shifted NREL-type stages). The forces on the planet are

        from the sun:   s F_bt cos(a_w,sp) t_j + F_bt sin(a_w,sp) r_j + h_p s F_bt tan(b_b) x    at the sun pitch point
        from the ring:  s F_bt cos(a_w,rp) t_j - F_bt sin(a_w,rp) r_j - h_p s F_bt tan(b_b) x    at the ring pitch point

    (s = +1/-1 the sense of the sun's external torque, which the planets' tangential forces on the sun
    oppose; h_p the planet's hand: an axial force on a gear is -h (F_tang . t_P) tan(b_w) x, t_P = x X (axis to
    contact point)). The sun takes the reverse of the first, the ring the reverse of the second, the carrier
    (through the pins) the sum; a planet's pin bearings hold the planet against both.

    Losses: with a stage efficiency below 1 the member torques leave the lossless ratio 1 : u : -(1 + u), and
    each member's forces are scaled so that they carry its own torque of the moment balance (``side_factors``,
    per unit F_bt of the sun mesh): the sun |T_s| / (N r_b,s F_bt), the ring |T_r| / (N r_b,r F_bt), and the
    planet, on both its meshes, |T_c| / (N (r_b,s + r_b,r) F_bt), so that its pin carries exactly the carrier's
    torque (N F_bt (r_b,s + r_b,r) is the carrier torque of the forces above). All 1 without losses."""

    stage: int  # 0-based
    planets: int
    psi_rad: tuple[float, ...]
    r_w_sun_mm: float  # sun's working pitch radius in the sun mesh
    r_w_planet_sun_mm: float  # planet's, sun mesh
    r_w_planet_ring_mm: float  # planet's, ring mesh
    r_w_ring_mm: float  # ring's, ring mesh
    alpha_w_sun_rad: float
    alpha_w_ring_rad: float
    base_helix_rad: float
    planet_hand: int  # +1 right, -1 left, 0 spur
    torque_sense: int  # s: the sign of the sun's external torque about +x at the design's load
    shafts: dict[str, int]  # member -> 1-based shaft (the held member: none)
    axial_mm: dict[str, float | None]  # member -> the gear centre's x (the carrier's: the planets')
    load_sharing_factor: float  # K_gamma: the most loaded planet's share over the mean (planet pins only)
    output_sense: int = 1  # the output member's sense of rotation against the input member's (Willis)
    input_share_sign: int = 1  # the sign of the input member's torque share (sun 1 : ring u : carrier -(1 + u))
    side_factors: tuple[float, float, float] = (1.0, 1.0, 1.0)  # sun, planet, ring: the forces per unit F_bt (losses)

    @property
    def centre_distance_mm(self) -> float:
        return self.r_w_sun_mm + self.r_w_planet_sun_mm

    def planet_loads(self, j: int, line_force_N: float, about_planet: bool = False,
                     sides: tuple[float, float] | None = None) -> tuple[PointLoad, PointLoad]:
        """The sun's and the ring's force on planet j for the sun mesh's line force F_bt (positive: the design's
        load direction), at the pitch points in the global frame (``about_planet``: relative to the planet's
        axis, x along the pin); ``sides``: the factors on the sun mesh's and the ring mesh's F_bt (default: the
        planet's, :attr:`side_factors`)."""
        psi = self.psi_rad[j]
        r = (0.0, math.cos(psi), math.sin(psi))
        t = (0.0, -math.sin(psi), math.cos(psi))
        s, h = self.torque_sense, self.planet_hand
        f_sun, f_ring = ((self.side_factors[1],) * 2 if sides is None else sides)
        f_ts = f_sun * line_force_N * math.cos(self.alpha_w_sun_rad)  # tangential, each mesh at its working circle
        f_tr = f_ring * line_force_N * math.cos(self.alpha_w_ring_rad)
        radial_s = f_sun * abs(line_force_N) * math.sin(self.alpha_w_sun_rad)
        radial_r = f_ring * abs(line_force_N) * math.sin(self.alpha_w_ring_rad)
        axial = h * s * line_force_N * math.tan(self.base_helix_rad)  # F_bt tan(b_b) on each mesh, opposite senses
        from_sun = (f_sun * axial, s * f_ts * t[1] + radial_s * r[1], s * f_ts * t[2] + radial_s * r[2])
        from_ring = (-f_ring * axial, s * f_tr * t[1] - radial_r * r[1], s * f_tr * t[2] - radial_r * r[2])
        x = self.axial_mm["planet"] or 0.0
        centre = 0.0 if about_planet else self.centre_distance_mm
        at_sun = centre - self.r_w_planet_sun_mm
        at_ring = centre + self.r_w_planet_ring_mm
        return (PointLoad((x, at_sun * r[1], at_sun * r[2]), from_sun),
                PointLoad((x, at_ring * r[1], at_ring * r[2]), from_ring))

    def member_loads(self, member: str, line_force_N: float) -> list[PointLoad]:
        """The planets' forces on a central member (sun, ring, carrier) at their points, its own axial place."""
        out: list[PointLoad] = []
        x = self.axial_mm[member]
        sides = {"sun": (self.side_factors[0],) * 2, "ring": (self.side_factors[2],) * 2}.get(member)
        for j in range(self.planets):
            sun, ring = self.planet_loads(j, line_force_N, sides=sides)
            if member == "sun":
                out.append(PointLoad((x or 0.0, *sun.point_mm[1:]), _neg(sun.force_N)))
            elif member == "ring":
                out.append(PointLoad((x or 0.0, *ring.point_mm[1:]), _neg(ring.force_N)))
            else:  # the carrier through the pins: what the planet passes on
                out += [sun, ring]
        return out


ROUND_OFF = 1e-12  # a central member's reaction component below this share of its loads' sum is round-off


def _snapped(r: Reaction, scale: float) -> Reaction:
    return Reaction(*(0.0 if abs(c) <= scale else c for c in (r.y_N, r.z_N, r.axial_N)))


def _neg(f: Vec) -> Vec:
    return (-f[0], -f[1], -f[2])


@record
class ShaftLayout:
    """The supported shafts of a design: which mesh loads act on which shaft, and its two bearings."""

    meshes: tuple[MeshLayout, ...]
    shafts: dict[int, tuple[BearingSpec, BearingSpec]]  # 1-based shaft -> (A, B)
    planetaries: tuple[PlanetaryLayout, ...] = ()
    pins: dict[int, tuple[BearingSpec, BearingSpec]] = field(default_factory=dict)  # 1-based planetary stage -> (A, B)

    @property
    def specs(self) -> list[BearingSpec]:
        """Every bearing (shafts' and planet pins'), in [[bearing]] order."""
        pairs = list(self.shafts.values()) + list(self.pins.values())
        return sorted((s for pair in pairs for s in pair), key=lambda s: s.index)

    def loads_on(self, shaft: int, line_forces_N: Sequence[float]) -> list[PointLoad]:
        """Shaft j (1-based) carries pinion j (stage j-1, 0-based) and gear j-1 (stage j-2), or a planetary
        stage's member (its input member on shaft k+1, its output member on shaft k+2 for stage k, 0-based)."""
        out: list[PointLoad] = []
        for m in self.meshes:
            if m.stage + 1 == shaft or m.stage + 2 == shaft:
                pl, gl = mesh_loads(m, line_forces_N[m.stage])
                out.append(pl if m.stage + 1 == shaft else gl)
        for p in self.planetaries:
            for member, on in p.shafts.items():
                if on == shaft:
                    out += p.member_loads(member, line_forces_N[p.stage])
        return out

    def pin_loads(self, stage: int, line_forces_N: Sequence[float], sharing: bool = True) -> list[PointLoad]:
        """The mesh forces on planet 1 of planetary stage ``stage`` (1-based) about its own axis (x along the pin,
        y towards its centre's radial direction, z tangential), times the load-sharing factor (``sharing``)."""
        p = next(q for q in self.planetaries if q.stage + 1 == stage)
        factor = p.load_sharing_factor if sharing else 1.0
        return list(p.planet_loads(0, factor * line_forces_N[p.stage], about_planet=True))

    def reactions(self, line_forces_N: Sequence[float], sharing: bool = True) -> list[tuple[BearingSpec, Reaction]]:
        """Every bearing's reaction, in [[bearing]] order, for the stages' line-of-action forces F_bt (a planetary
        stage: per planet, its sun mesh's, positive in the design's load direction; ``sharing``: a planet pin
        carries the load-sharing factor times the mean planet's)."""
        found: list[tuple[BearingSpec, Reaction]] = []
        central = {on for p in self.planetaries for on in p.shafts.values()}
        for shaft, (a, b) in self.shafts.items():
            loads = self.loads_on(shaft, line_forces_N)
            ra, rb = shaft_reactions(loads, a.position_mm, b.position_mm, a.locating)
            if shaft in central:  # the planets' balanced radial forces cancel to round-off: that is zero
                scale = ROUND_OFF * sum(abs(c) for ld in loads for c in ld.force_N)
                ra, rb = _snapped(ra, scale), _snapped(rb, scale)
            found += [(a, ra), (b, rb)]
        for stage, (a, b) in self.pins.items():
            ra, rb = shaft_reactions(self.pin_loads(stage, line_forces_N, sharing), a.position_mm, b.position_mm,
                                     a.locating)
            found += [(a, ra), (b, rb)]
        return sorted(found, key=lambda pair: pair[0].index)


def layout(cfg: DesignFile, working_radii_mm: Sequence[tuple[float, float]],
           working_pressure_rad: Sequence[float], base_helix_rad: Sequence[float],
           planetaries: Sequence[PlanetaryLayout | None] = ()) -> ShaftLayout | None:
    """The shaft layout of a design file with ``[[bearing]]`` tables (None without). Raises DesignError
    naming the key for a bearing on a shaft that does not exist, a shaft without exactly two bearings or
    one locating bearing, two bearings at one position, or a gear on a supported shaft without
    ``axial_position_mm``. ``planetaries``: per stage, the layout of a stage with planets (:func:`stage_layout`
    gives every stage's: :func:`planetary_layout`) or None."""
    if not cfg.bearing:
        return None
    n_shafts = len(cfg.stage) + 1
    by_shaft: dict[int, list[BearingSpec]] = {}
    by_pin: dict[int, list[BearingSpec]] = {}
    for j, b in enumerate(cfg.bearing):
        if b.planet_stage is not None:
            k = b.planet_stage
            if k > len(cfg.stage):
                raise DesignError(f"stage {k} does not exist: this train has stages 1 to {len(cfg.stage)} (planet_stage "
                                  "names the planetary stage whose planet pins carry the bearing, 1-based)",
                                  key=f"bearing[{j}].planet_stage")
            if k > len(planetaries) or planetaries[k - 1] is None:  # no planets there
                raise DesignError(f"stage {k} is not a planetary stage: planet_stage names the planetary stage whose "
                                  "planet pins carry the bearing (1-based)", key=f"bearing[{j}].planet_stage")
            by_pin.setdefault(k, []).append(_spec(j, b, 0, k))
            continue
        assert b.shaft is not None  # the schema asks for exactly one of shaft and planet_stage
        if b.shaft > n_shafts:
            raise DesignError(f"shaft {b.shaft} does not exist: this train has shafts 1 to {n_shafts} (1 = the input "
                              "shaft, k+1 = gear k with pinion k+1)", key=f"bearing[{j}].shaft")
        by_shaft.setdefault(b.shaft, []).append(_spec(j, b, b.shaft))
    shafts = {s: _pair(f"shaft {s}", specs) for s, specs in sorted(by_shaft.items())}
    pins = {k: _pair(f"the planet pins of stage {k}", specs) for k, specs in sorted(by_pin.items())}
    sense = 1 if cfg.input.rotation == "cw" else -1  # the sense of rotation of the stage's input shaft
    meshes = []
    planetary_layouts: list[PlanetaryLayout] = []
    for k in range(len(cfg.stage)):
        pl = planetaries[k] if k < len(planetaries) else None
        if pl is not None:  # a stage with planets (its layout from its design)
            p_stage = cfg.stage[k]
            if k + 1 in pins and p_stage.planet.axial_position_mm is None:  # type: ignore[union-attr]
                raise DesignError(f"the planet pins of stage {k + 1} have bearings (planet_stage = {k + 1}), so the "
                                  "planets need their axial position (the gear centre along the pin, from the housing "
                                  "plane the bearings' position_mm is measured from)",
                                  key=f"stage[{k}].planet.axial_position_mm")
            for member, shaft in pl.shafts.items():
                where = "planet" if member == "carrier" else member
                if shaft in shafts and pl.axial_mm[member] is None:
                    raise DesignError(f"shaft {shaft} has bearings, so the {member}'s gear plane needs its axial "
                                      f"position", key=f"stage[{k}].{where}.axial_position_mm")
            # the driven member's external torque has the sense of its rotation; the sun's follows by its share
            pl = replace(pl, torque_sense=sense * pl.input_share_sign)
            planetary_layouts.append(pl)
            sense = sense * pl.output_sense
            continue
        stage = cfg.pair(k)
        phi = math.radians(stage.center_angle_deg)
        u = (0.0, math.cos(phi), math.sin(phi))
        hand = {"right": 1, "left": -1}.get(stage.pinion.hand or "spur", 0) if stage.helix_angle_deg > 0 else 0
        positions = (stage.pinion.axial_position_mm, stage.gear.axial_position_mm)
        for member, shaft, pos in (("pinion", k + 1, positions[0]), ("gear", k + 2, positions[1])):
            if shaft in shafts and pos is None:
                raise DesignError(f"shaft {shaft} has bearings, so its {member} needs its axial position (the gear "
                                  "centre along x from the housing plane)", key=f"stage[{k}].{member}.axial_position_mm")
        meshes.append(MeshLayout(k, u, cross((1.0, 0.0, 0.0), u), sense, hand, working_pressure_rad[k],
                                 base_helix_rad[k], tuple(working_radii_mm[k]), positions))  # type: ignore[arg-type]
        sense = -sense
    return ShaftLayout(tuple(meshes), shafts, tuple(planetary_layouts), pins)


PIN_REACH = 2.0  # a pin bearing farther from the planet's mid-face than this x max(face width, pitch diameter)


def pin_bearing_warnings(cfg: DesignFile, stages: Sequence[StageResult]) -> list[tuple[str, dict]]:
    """A planet pin's bearing implausibly far from its planet (more than ``PIN_REACH`` x the larger of the planet's
    face width and pitch diameter from its mid-face): (message, data) per bearing."""
    out = []
    for j, b in enumerate(cfg.bearing):
        k = b.planet_stage
        if k is None or k > len(stages) or not design_kind(stages[k - 1]).shares_load:  # a stage with planets
            continue
        planet_cfg = cfg.stage[k - 1].planet  # type: ignore[union-attr]
        if planet_cfg.axial_position_mm is None:
            continue
        planet = stages[k - 1].planetary.planet  # type: ignore[union-attr]
        reach = PIN_REACH * max(planet.face_width_mm, planet.pitch_diameter_mm)
        distance = abs(b.position_mm - planet_cfg.axial_position_mm)
        if distance > reach:
            out.append((f"bearing {j + 1}: a planet pin bearing of stage {k} sits {distance:.4g} mm from its planet's "
                        f"mid-face (planet.axial_position_mm = {planet_cfg.axial_position_mm:g} mm), more than "
                        f"{reach:.4g} mm ({PIN_REACH:g} x the planet's larger of face width and pitch diameter): a pin "
                        f"that long is implausible; check bearing[{j}].position_mm (measured from the same housing plane)",
                        {"bearing": j + 1, "stage": k, "distance_mm": distance, "limit_mm": reach}))
    return out


def _pair(shaft: str, specs: list[BearingSpec]) -> tuple[BearingSpec, BearingSpec]:
    first = f"bearing[{specs[0].index}]"
    place = "planet_stage" if specs[0].planet_stage else "shaft"
    if len(specs) != 2:
        raise DesignError(f"{shaft} has {len(specs)} bearing(s): a shaft rests on exactly two (one locating, "
                          "one floating)", key=f"{first}.{place}")
    locating = [s for s in specs if s.locating]
    if len(locating) != 1:
        raise DesignError(f"{shaft} has {len(locating)} locating bearings: exactly one of its two bearings "
                          "takes the axial force (locating = true)", key=f"{first}.locating")
    if specs[0].position_mm == specs[1].position_mm:
        raise DesignError(f"the two bearings of {shaft} sit at the same position_mm: the shaft needs a span",
                          key=f"bearing[{specs[1].index}].position_mm")
    a, b = sorted(specs, key=lambda s: s.position_mm)
    return a, b


# ------------------------------------------------------------------------------------ design results
def stage_layout(cfg: DesignFile, stages: Sequence[StageResult]) -> ShaftLayout | None:
    """The shaft layout from the design's stage geometry (working pitch radii r_w = r_b / cos a_wt); None without
    ``[[bearing]]`` tables. The statics know gear stages: a stage of a kind without a gear pair (a belt) and
    bearings are exit 2 naming the stage."""
    if not cfg.bearing:
        return None
    other = [k for k, s in enumerate(stages) if not design_kind(s).gear_pair]
    if other:
        raise DesignError(f"[[bearing]]: the shaft statics know gear stages only, and stage {other[0] + 1} is of type "
                          f"{getattr(stages[other[0]], 'type', '?')!r}: remove the bearing tables",
                          key=f"stage[{other[0]}].type")
    alphas = [math.radians(s.working_pressure_angle_deg) for s in stages]
    radii = [(0.5 * s.pinion.base_diameter_mm / math.cos(a), 0.5 * s.gear.base_diameter_mm / math.cos(a))
             for s, a in zip(stages, alphas, strict=True)]
    return layout(cfg, radii, alphas, [math.radians(s.base_helix_angle_deg) for s in stages],
                  [planetary_layout(cfg, k, s) if design_kind(s).shares_load else None for k, s in enumerate(stages)])


def planetary_layout(cfg: DesignFile, k: int, st: StageResult) -> PlanetaryLayout:
    """A planetary stage's statics layout from its design; the sense of its torque is set by :func:`layout` from
    the train's senses of rotation."""
    p = st.planetary
    assert p is not None  # a stage whose planets share its load (stage_layout asks its kind)
    stage = cast("PlanetaryStage", cfg.stage[k])  # the table of the stage whose design has planets
    a_sp = math.radians(st.working_pressure_angle_deg)
    a_rp = math.radians(p.planet_ring.working_pressure_angle_deg)
    hand = {"right": 1, "left": -1}.get(stage.planet.hand or "spur", 0) if st.helix_angle_deg > 0 else 0
    unit = willis_speeds(p.sun.teeth, p.ring.teeth, p.fixed, p.input)
    u = p.ring.teeth / p.sun.teeth
    share = {"sun": 1.0, "ring": u, "carrier": -(1.0 + u)}[p.input]
    n = p.planet_count
    return PlanetaryLayout(
        side_factors=_side_factors(st),
        stage=k, planets=n, psi_rad=tuple(math.radians(a) for a in p.planet_angles_deg or planet_angles_deg(n, None)),
        r_w_sun_mm=0.5 * p.sun.base_diameter_mm / math.cos(a_sp),
        r_w_planet_sun_mm=0.5 * p.planet.base_diameter_mm / math.cos(a_sp),
        r_w_planet_ring_mm=0.5 * p.planet.base_diameter_mm / math.cos(a_rp),
        r_w_ring_mm=0.5 * p.ring.base_diameter_mm / math.cos(a_rp), alpha_w_sun_rad=a_sp, alpha_w_ring_rad=a_rp,
        base_helix_rad=math.radians(st.base_helix_angle_deg), planet_hand=hand, torque_sense=1,
        shafts={p.input: k + 1, p.output: k + 2},
        axial_mm={"sun": stage.sun.axial_position_mm, "ring": stage.ring.axial_position_mm,
                  "carrier": stage.planet.axial_position_mm, "planet": stage.planet.axial_position_mm},
        load_sharing_factor=p.load_sharing_factor, output_sense=1 if unit[p.output] > 0 else -1,
        input_share_sign=1 if share > 0 else -1)


def _side_factors(st: StageResult) -> tuple[float, float, float]:
    """The sun's, the planet's and the ring's forces per unit F_bt of the sun mesh that carry the moment balance's
    torques (:class:`PlanetaryLayout`); exactly 1 without losses or without a load (no balance to scale by)."""
    p = st.planetary
    assert p is not None
    f_bt = abs(line_forces_N([st])[0])
    torques = {m: 1e3 * abs(v) for m, v in p.moment_balance_Nm.items()}
    if p.mesh_efficiency >= 1.0 or f_bt == 0.0 or not all(math.isfinite(v) for v in torques.values()):
        return (1.0, 1.0, 1.0)
    r_bs, r_br = 0.5 * p.sun.base_diameter_mm, 0.5 * p.ring.base_diameter_mm
    per_planet = p.planet_count * f_bt
    return (torques["sun"] / (per_planet * r_bs), torques["carrier"] / (per_planet * (r_bs + r_br)),
            torques["ring"] / (per_planet * r_br))


def line_forces_N(stages: Sequence[StageResult]) -> list[float]:
    """F_bt = T_1 / r_b1 per stage from the pinion torques (N·mm / mm); a planetary stage's per planet (its sun
    mesh's), as a magnitude in the design's load direction."""
    out = []
    for s in stages:
        f = s.pinion.torque_Nmm / (0.5 * s.pinion.base_diameter_mm)
        out.append(abs(f) if design_kind(s).model_signs_forces else f)
    return out


def bearing_results(cfg: DesignFile, stages: Sequence[StageResult],
                    shaft_speeds_rpm: Sequence[float]) -> tuple[BearingResult, ...]:
    """Static reactions and ISO 281 lives of every ``[[bearing]]`` at the design's load (empty without); a
    planet pin's bearing turns at the planet's speed relative to the carrier."""
    lay = stage_layout(cfg, stages)
    if lay is None:
        return ()

    check_inputs(cfg)
    lub = lubrication(cfg)
    out = []
    for spec, r in lay.reactions(line_forces_N(stages)):
        if spec.planet_stage:
            planetary = stages[spec.planet_stage - 1].planetary
            assert planetary is not None
            speed = planetary.planet.speed_rpm
        else:
            speed = shaft_speeds_rpm[spec.shaft - 1]
        out.append(bearing_result(spec, r, speed, lub))
    return tuple(out)


def bearing_result(spec: BearingSpec, r: Reaction, speed_rpm: float, lub: Lubrication | None = None) -> BearingResult:
    """One bearing's figures at the reaction ``r``: P, L10 and, with their keys, ISO 76's P_0 and s_0 and ISO 281's
    kappa, a_ISO, a_1 and L_nm (``lub``: the oil, needed for those)."""
    p = equivalent_load_N(r.radial_N, r.axial_N, spec.e, spec.X, spec.Y)
    l10 = basic_life_Mrev(spec.rating_N, p, spec.kind)
    p0, s0 = static_figures(spec.static_rating_N, spec.X0, spec.Y0, r.radial_N, r.axial_N)
    extra: dict = {}
    if spec.static_rating_N is not None:
        extra.update(static_load_rating_kN=spec.static_rating_N / 1e3, static_equivalent_load_N=p0, static_safety=s0)
    if spec.fatigue_limit_N is not None and spec.pitch_diameter_mm is not None and lub is not None:
        m = modified_life(l10, p, speed_rpm, spec.kind, spec.fatigue_limit_N, spec.pitch_diameter_mm,
                          spec.reliability_percent, lub)
        extra.update(fatigue_load_limit_kN=spec.fatigue_limit_N / 1e3, pitch_diameter_mm=spec.pitch_diameter_mm,
                     reliability_percent=spec.reliability_percent, kappa=m.kappa, a_ISO=m.a_ISO, a_1=m.a_1,
                     L_nm_Mrev=m.L_nm_Mrev, L_nm_h=life_hours(m.L_nm_Mrev, speed_rpm))
    return BearingResult(shaft=spec.shaft, position_mm=spec.position_mm, radial_N=r.radial_N, radial_y_N=r.y_N,
                         radial_z_N=r.z_N, axial_N=r.axial_N, equivalent_load_N=p, L10_Mrev=l10,
                         L10_h=life_hours(l10, speed_rpm), kind=spec.kind, locating=spec.locating,
                         dynamic_load_rating_kN=spec.rating_N / 1e3, speed_rpm=abs(speed_rpm),
                         planet_stage=spec.planet_stage or None, **extra)
