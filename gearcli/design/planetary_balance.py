"""A planetary stage's books: the moment balance with losses, the meshes' efficiency, the assembly checks
(docs/planetary.md, "Losses and the moment balance", "Assembly").

Losses. The stage's ``efficiency`` η is its power efficiency |P_out| / |P_in| in the design's power flow, as
for a parallel stage. It is lost in the planets' meshes, in the carrier's frame (where each mesh is a fixed-axis
pair): every sun–planet and planet–ring mesh transmits its rolling power with the same efficiency η_m, so the
stage's basic (carrier-held) efficiency is η_0 = η_m². On each mesh the driving member's side carries the mesh's
force F and the driven side η_m F (the parallel stage's loss law, :mod:`gearcli.model.elements.mesh`); the planet
spins freely, so its two meshes' planet-side forces are equal. In the carrier's frame power flows from the sun to
the ring or from the ring to the sun; with T_sun and T_ring the external torques on those members:

    sun drives (carrier frame):   |T_ring| = η_0 (z_r/z_s) |T_sun|,   F_pr = η_m F_sp
    ring drives:                  |T_ring| = (z_r/z_s) |T_sun| / η_0, F_sp = η_m F_pr

and the carrier takes the rest, T_sun + T_carrier + T_ring = 0 exactly (the friction forces are internal). η_0 is
solved from η (it is a known closed form per arrangement, e.g. sun in, ring held: η = (1 + η_0 u)/(1 + u),
u = z_r/z_s; the bisection below covers every arrangement and either power flow with one code).

Signs: a member's signed torque is the external torque on it, positive in the running sense of the stage's input
member (the sense of the members' signed speeds): the input member's torque is positive for a positive load.
"""

from __future__ import annotations

import math

from gearcli.core.records import record
from gearcli.errors import DesignError

MEMBERS = ("sun", "carrier", "ring")
CONCENTRICITY_TOLERANCE_MODULES = 0.01  # |a_w,pr - a_w,sp| allowed, in normal modules
ANGLE_TOLERANCE_DEG = 1e-6  # two planet gaps alike (equal spacing) within this
# a declared planet angle is assemblable within this fraction of the step 360/(z_s + z_r) of a whole multiple of it
# (then taken as that multiple): 1e-4 of a step is a mesh phase error below 1e-4 z_s/(z_s + z_r) of a cycle and
# lets an angle typed to the digits a drawing gives (e.g. 276.923° for 3.6/1.04 x 80) pass, which 1e-6° did not
ANGLE_TOLERANCE_STEPS = 1e-4


def willis_speeds(z_sun: int, z_ring: int, fixed: str, driven: str) -> dict[str, float]:
    """Signed member speeds for a unit speed of ``driven`` with ``fixed`` at rest, from Willis' equation
    ω_s = (1 + u) ω_c − u ω_r, u = z_r/z_s (a planetary's three members keep one degree of freedom)."""
    u = z_ring / z_sun
    motions = ({"sun": -u, "carrier": 0.0, "ring": 1.0},  # carrier held
               {"sun": 1.0 + u, "carrier": 1.0, "ring": 0.0},  # ring held
               {"sun": 0.0, "carrier": u, "ring": 1.0 + u})  # sun held
    motion = next(m for m in motions if m[fixed] == 0.0)
    return {m: v / motion[driven] for m, v in motion.items()}


def willis(z_sun: int, z_ring: int, fixed: str, driven: str) -> dict[str, float]:
    """Signed member speeds for a unit speed of ``driven`` (no negative zero)."""
    return {m: v + 0.0 for m, v in willis_speeds(z_sun, z_ring, fixed, driven).items()}


@record
class Balance:
    """The stage's statics per unit |T_sun|: signed member torques, which member drives in the carrier frame,
    the sun–planet and planet–ring mesh forces (the driving side's, N r_b F in units of |T_sun| / r_bs ...)."""

    torques: dict[str, float]  # signed external torques, T_sun + T_carrier + T_ring = 0
    sun_drives: bool  # in the carrier's frame: power flows sun -> planet -> ring
    sun_mesh: float  # N r_bs F_sp / |T_sun|: the sun–planet mesh's (driving-side) force
    ring_mesh: float  # N r_bs F_pr / |T_sun|: the planet–ring mesh's, on the same lever (r_br F = u r_bs F)
    efficiency: float  # |P_out| / |P_in| of the stage


def balance(z_sun: int, z_ring: int, fixed: str, driven: str, mesh_efficiency: float, load_sign: float = 1.0) -> Balance:
    """The moment balance with losses (module text) for |T_sun| = 1 and a load of sign ``load_sign``."""
    out = next(m for m in MEMBERS if m not in (fixed, driven))
    w = willis(z_sun, z_ring, fixed, driven)
    u = z_ring / z_sun
    eta0 = mesh_efficiency ** 2
    # T_sun and T_ring share a sign, sigma; the driven member's torque is along its motion (positive load)
    sigma = 1.0 if driven in ("sun", "ring") else -1.0
    sigma *= 1.0 if load_sign >= 0.0 else -1.0
    sun_drives = sigma * (w["sun"] - w["carrier"]) > 0.0
    ring = u * eta0 if sun_drives else u / eta0
    torques = {"sun": sigma, "ring": sigma * ring, "carrier": -sigma * (1.0 + ring)}
    if sun_drives:
        sun_mesh, ring_mesh = 1.0, mesh_efficiency
    else:
        sun_mesh, ring_mesh = 1.0 / mesh_efficiency, 1.0 / eta0
    p_in, p_out = abs(torques[driven] * w[driven]), abs(torques[out] * w[out])
    if load_sign < 0.0:
        p_in, p_out = p_out, p_in
    return Balance(torques, sun_drives, sun_mesh, ring_mesh, p_out / p_in)


def mesh_efficiency(z_sun: int, z_ring: int, fixed: str, driven: str, efficiency: float, key: str) -> float:
    """η_m with which the stage's power efficiency is ``efficiency`` in the design's power flow (bisection: the
    stage's efficiency rises monotonically with η_m); DesignError where no η_m in (0, 1] gives it."""
    if efficiency >= 1.0:
        return 1.0

    def eff(eta_m: float) -> float:
        return balance(z_sun, z_ring, fixed, driven, eta_m).efficiency

    lowest = eff(1e-9)
    if efficiency <= lowest:
        raise DesignError(f"a planetary stage with this arrangement (held {fixed}, driven {driven}) has a power "
                          f"efficiency above {lowest:.4g} whatever its meshes lose: "
                          f"efficiency = {efficiency:g} cannot be reached", key=key)
    lo, hi = 1e-9, 1.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if eff(mid) < efficiency:
            lo = mid
        else:
            hi = mid
        if hi - lo <= 1e-16:
            break
    return 0.5 * (lo + hi)


# ----------------------------------------------------------------------------------------------- assembly
def planet_angles_deg(count: int, given: list[float] | None, step_deg: float | None = None) -> list[float]:
    """Each planet's position on the carrier: the declared ``planet.angles_deg`` (with ``step_deg`` = 360/(z_s + z_r),
    each snapped to the whole multiple of the step from planet 1 that :func:`check_assembly` accepted) or equal
    spacing."""
    if given:
        first = float(given[0])
        if step_deg is None:
            return [float(a) for a in given]
        return [first + round((a - first) / step_deg) * step_deg for a in given]
    return [360.0 * j / count for j in range(count)]


def check_assembly(k: int, z_s: int, z_r: int, count: int, given_angles: list[float] | None,
                   a_sun_planet: float, a_planet_ring: float, planet_tip_mm: float, normal_module: float) -> None:
    """Spacing, concentricity and adjacency of planetary stage k: DesignError (exit 2) naming the check and the
    numbers where the stage cannot be assembled."""
    key = f"stage[{k}]"
    step = 360.0 / (z_s + z_r)  # the angles at which a planet meshes with both sun and ring
    if given_angles is None:
        if (z_s + z_r) % count:
            raise DesignError(
                f"planet spacing: (z_s + z_r)/N = ({z_s} + {z_r})/{count} = {(z_s + z_r) / count:.4g} is not a whole "
                f"number, so {count} planets cannot be equally spaced; change the teeth, or declare the planets' "
                f"positions with planet.angles_deg (whole multiples of 360/(z_s + z_r) = {step:.6g}°)",
                key=f"{key}.planet.count")
    else:
        _check_angles(key, given_angles, count, step)
    tol = CONCENTRICITY_TOLERANCE_MODULES * normal_module
    if abs(a_planet_ring - a_sun_planet) > tol:
        raise DesignError(
            f"concentricity: the planet–ring working centre distance a_w = {a_planet_ring:.4f} mm differs from the "
            f"sun–planet one a_w = {a_sun_planet:.4f} mm by {a_planet_ring - a_sun_planet:+.4f} mm (allowed "
            f"{tol:.3g} mm = 0.01 m_n): the planets cannot sit on one carrier radius; adjust the profile shifts "
            "(z_r - z_s = 2 z_p for zero shifts)", key=f"{key}.ring.profile_shift")
    angles = sorted(a % 360.0 for a in planet_angles_deg(count, given_angles, step))
    if count > 1:
        gaps = [(angles[(j + 1) % count] - angles[j]) % 360.0 or 360.0 for j in range(count)]
        gap = min(gaps)
        room = 2.0 * a_sun_planet * math.sin(math.radians(gap) / 2.0)
        if room <= planet_tip_mm:
            declared = given_angles is not None  # the declared angles place the clashing pair, not the count
            raise DesignError(
                f"adjacency: neighbouring planets {gap:.4g}° apart have centres {room:.4f} mm apart "
                f"(2 a sin(Δψ/2), a = {a_sun_planet:.4f} mm), not more than the planet's tip diameter "
                f"d_a = {planet_tip_mm:.4f} mm: their tip circles overlap by {planet_tip_mm - room:.4g} mm; "
                + ("spread the declared angles, or " if declared else "") + "fewer or smaller planets",
                key=f"{key}.planet.{'angles_deg' if declared else 'count'}")


def _check_angles(key: str, angles: list[float], count: int, step: float) -> None:
    where = f"{key}.planet.angles_deg"
    if len(angles) != count:
        raise DesignError(f"planet.angles_deg needs one angle per planet ({count}), got {len(angles)}", key=where)
    first = angles[0]
    seen: set[int] = set()
    for j, a in enumerate(angles):
        steps = (a - first) / step
        whole = round(steps)
        if abs(steps - whole) > ANGLE_TOLERANCE_STEPS:
            raise DesignError(
                f"planet {j + 1} at {a:.10g}°: a planet meshes with both sun and ring only at whole multiples of "
                f"360/(z_s + z_r) = {step:.10g}° from planet 1 ({first:.10g}°), within {ANGLE_TOLERANCE_STEPS:g} of "
                f"that step; the nearest are {first + math.floor(steps) * step:.6f}° and "
                f"{first + math.ceil(steps) * step:.6f}°", key=where)
        slot = whole % round(360.0 / step)
        if slot in seen:
            raise DesignError(f"planet {j + 1} at {a:g}°: two planets at the same position", key=where)
        seen.add(slot)
