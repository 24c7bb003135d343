"""Natural frequencies, mode shapes and modal strain-energy shares of the linearised chain.

Linearised at the static full load (each element's tangent stiffness from its own force law,
:func:`gearcli.model.linear.tangent`; a mesh at its mean stiffness; when a Hertzian mesh carries no
static load, at the rigid-body run-up load instead, as the simulation's reported frequencies), the
undamped chain obeys ``J theta'' + R^T K R theta = 0`` over the body angles (R: deflections from
angles, ``delta = R theta``). Two boundaries:

- ``clamped_input``: the input body (the motor, or the input pinion without one) held — a speed drive;
- ``free``: every body free — a torque drive; its first mode is the rigid-body rotation at 0 Hz.

Each mode: frequency, shape (body angles, normalised to the largest |entry| = 1, that entry
positive), each connector's share of the modal strain energy ``k_c (R phi)_c^2 / sum`` (sums to 1),
and the excitations that cross it while the input body runs from 0 to ``SPEED_RANGE`` x its nominal speed: the
orders (1x, 2x, 3x each stage's mesh frequency, 1x each reducer shaft's rotation, each order of an input torque
ripple: lines through the origin of the Campbell diagram) and each load fluctuation frequency (a horizontal line,
independent of speed: it "crosses" a mode within ``RESONANCE_BAND`` of it at every speed, ``input_speed_rpm`` None).

Participation. A transmission error e at mesh c (or a shaft's runout, a 1x error at the meshes its gears
take part in) drives mode j (mass-normalised shape phi, modal damping ratio zeta_j) with the modal force
k_c (R phi)_c e; at resonance the mode's force in that mesh is k_c e s_cj / (2 zeta_j), s_cj the mesh's share of
the mode's strain energy (k_c (R phi)_c^2 / omega_j^2). So a crossing is excited as strongly as
``s / (2 zeta)`` (:attr:`Crossing.amplification`, the resonant force over the mesh's blocked error force k_c e;
the quasi-static response of the whole chain is at most 1): a mode whose strain energy sits in another
element is hardly excited by this mesh, however close the frequencies.

A harmonic torque T at body b (the input ripple at the input body, the load fluctuation at the load body) drives
mode j with the modal force phi_bj T (phi mass-normalised, sum_b J_b phi_b^2 = 1): at resonance the modal
coordinate is phi_bj T / (2 zeta_j omega_j^2) and the body's inertia torque in the mode J_b omega_j^2 phi_bj q_j =
J_b phi_bj^2 T / (2 zeta_j). So the participation of a torque is the excited body's share of the mode's kinetic
energy J_b phi_bj^2 (0 at a node of the mode, 1 for a single body on a spring) and its amplification
J_b phi_bj^2 / (2 zeta_j), the resonant inertia torque of the body over the applied harmonic torque (a clamped
input body takes the ripple into the ground: participation 0).

Damping. zeta_j linearises what the simulation integrates (:mod:`gearcli.model.damping`): every element's
damping law at its static force, a motor's slip damping dT/dw and the load law's dT/dw at the operating point,
and the meshes' losses; it is ``-Re lambda / |lambda|`` of the damped eigenvalue whose shape matches mode j
(frequencies and shapes are the undamped ones; :attr:`Mode.damped_frequency_Hz` is where that eigenvalue rings).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, NamedTuple

import numpy as np

from gearcli.core.memo import remember
from gearcli.core.records import record
from gearcli.model import planet_excitation
from gearcli.model.assembly import Layout
from gearcli.model.damping import body_damping, body_matrices, lever_matrices, loss_factors, modal_damping
from gearcli.model.eigen import orthonormal_clusters, real_eigenpairs, rigid_mode_count, soft_modes_refined
from gearcli.model.elements.mesh import I_Z
from gearcli.model.linear import operating_forces, peak_rigid_forces, speed_map, tangent
from gearcli.model.planet_excitation import dominant_label, phased_participation, planet_phases, repeated_ranks

if TYPE_CHECKING:
    from gearcli.model.campbell import CampbellData

SPEED_RANGE = 1.2  # operating range: 0 .. 1.2 x the nominal input speed
MESH_ORDERS = (1, 2, 3)  # harmonics of each stage's mesh frequency
SHAFT_ORDERS = (1,)  # of each reducer shaft's rotation (runout, eccentricity)
WARN_AMPLIFICATION = 0.1  # a crossing whose resonant force reaches 10 % of the blocked error force is warned
STRONG_AMPLIFICATION = 1.0  # ... beyond the quasi-static response: strongly excited
RESONANCE_BAND = 0.10  # |f_excitation - f_mode| / f_mode that the simulation warns about
BOUNDARIES = ("clamped_input", "free")


SOURCES = ("mesh", "shaft", "input_torque_ripple", "load_fluctuation")  # Crossing.source


@record
class Crossing:
    """Where an excitation meets a mode: its Hz per input Hz, the input speed there, participation, amplification."""

    excitation: str  # "stage 1 mesh 1x", "shaft 2 1x", "input torque ripple order 2", "load fluctuation 14.5 Hz"
    hz_per_input_hz: float  # excitation frequency over the input body's rotation frequency (0: a fixed frequency)
    input_speed_rpm: float | None  # input body speed at which it meets the mode; None: at every speed (fixed Hz)
    participation: float = 0.0  # the exciting meshes' (largest) share of the mode's strain energy; a torque: the
    # excited body's share of the mode's kinetic energy
    amplification: float | None = None  # participation / (2 zeta): None when the mode is undamped (unbounded)
    source: str = "mesh"  # one of SOURCES
    order: float = 1.0  # the harmonic: of the mesh frequency, of the shaft's rotation, per input revolution (ripple)
    excitation_Hz: float | None = None  # a fixed frequency (load fluctuation); None for an order

    @property
    def speed_independent(self) -> bool:
        """A fixed frequency (a horizontal line on the Campbell diagram): near the mode at every speed."""
        return self.input_speed_rpm is None

    @property
    def strength(self) -> str:
        """"strongly" (beyond the quasi-static response), "moderately" (>= 10 % of it), "weakly"."""
        a = math.inf if self.amplification is None else self.amplification
        return "strongly" if a >= STRONG_AMPLIFICATION else "moderately" if a >= WARN_AMPLIFICATION else "weakly"


@record
class Mode:
    """One natural mode: frequency, shape, strain-energy shares, dominant element and crossings."""

    number: int  # 1-based, ascending frequency
    frequency_Hz: float
    rigid: bool
    shape: tuple[float, ...]  # per body
    energy_share: tuple[float, ...]  # per connector; all 0 for a rigid mode
    dominant: str  # label of the connector with the largest share ("" for a rigid mode)
    crossings: tuple[Crossing, ...]
    damping_ratio: float = 0.0  # modal, from the linearised element damping (0 for a rigid mode)
    damped_frequency_Hz: float | None = None  # Im lambda / 2 pi of damping_ratio's eigenvalue (None: rigid, overdamped)


@record
class ModalAnalysis:
    """The modes of the linearised chain at one boundary condition."""

    boundary: str
    bodies: tuple[str, ...]
    connectors: tuple[str, ...]
    stiffness: tuple[float, ...]  # tangent stiffness per connector (N/m or N m/rad)
    modes: tuple[Mode, ...]
    nominal_input_rpm: float
    speed_range_rpm: tuple[float, float]


def connector_tangents(lay: Layout, duration_s: float) -> tuple[np.ndarray, np.ndarray]:
    """Tangent stiffness and damping of every connector at full load (planets at their settled shares)."""
    F = operating_forces(lay)
    kc = np.array([tangent(lay, c, F[c])[:2] for c in range(lay.n_conn)])
    if np.any(kc[:, 0] == 0.0):  # an unloaded Hertzian mesh: the run-up load, stiffest phase (as the simulation)
        op = np.maximum(np.abs(F), peak_rigid_forces(lay, duration_s))
        kc = np.array([tangent(lay, c, op[c], stiffest_phase=True)[:2] for c in range(lay.n_conn)])
    return kc[:, 0].copy(), kc[:, 1].copy()


def _stiffness(lay: Layout, duration_s: float) -> np.ndarray:
    return connector_tangents(lay, duration_s)[0]


class OrderSource(NamedTuple):
    """A mesh or shaft order: its name, its frequency over the input body's rotation frequency, the connectors it
    acts through, its kind (``"mesh"`` or ``"shaft"``), its harmonic and its stage (1-based; None for a shaft);
    ``phased``: a planetary stage's mesh order acts through all its planet meshes at once, each (connector, phase
    of its error at this harmonic in cycles), empty for any other order (:mod:`gearcli.model.planet_excitation`)."""

    name: str
    hz_per_input_hz: float
    via: tuple[int, ...]
    source: str
    order: float
    stage: int | None
    phased: tuple[tuple[int, float], ...] = ()


def excitation_sources(lay: Layout) -> list[OrderSource]:
    """(name, frequency over the input body's rotation frequency, connectors it acts through, ...) of every order:
    each stage's mesh orders act through that mesh (a stage whose connector is no mesh, a belt's span, has
    none); a shaft's rotation order through the meshes of the gears
    it carries (shaft 1: stage 1's pinion; shaft k + 1: stage k's gear and stage k + 1's pinion). Found once per
    layout (every mode's crossings and every resonance check read them)."""
    cache = lay.__dict__.setdefault("_excitation_sources", [])
    if not cache:  # what they are made of, the same for every point of a speed sweep: made once for them all
        key = _sources_key(lay)
        found = _SOURCES.get(key)
        cache.append(found if found is not None else remember(_SOURCES, key, _excitation_sources(lay)))
    return list(cache[0])


_SOURCES: dict[tuple, list[OrderSource]] = {}  # _excitation_sources by what it reads of a layout (_sources_key)


def _sources_key(lay: Layout) -> tuple:
    """Everything :func:`_excitation_sources` reads of ``lay``: the stages' connectors, their roles, tooth counts and
    driving bodies' ratios, the shafts' bodies and ratios (the sources are records: shared, never changed)."""
    stages = tuple(lay.stage_conn)
    return (stages, tuple((lay.connectors[c].role, float(lay.connectors[c].params[I_Z]),
                           lay.bodies[lay.connectors[c].a].ratio) for c in stages),
            tuple((b, lay.bodies[b].ratio) for b in lay.shaft_body), planet_phases(lay))


def _excitation_sources(lay: Layout) -> list[OrderSource]:
    out: list[OrderSource] = []
    stages = lay.stage_conn
    phases = planet_phases(lay)
    for k, c in enumerate(stages):
        x = lay.connectors[c]
        planets = [(i, ph) for stage, i, ph in phases if stage == x.index] if x.planet >= 0 else []
        for h in MESH_ORDERS if x.role == "mesh" else ():
            phased = tuple((i, (h * ph) % 1.0) for i, ph in planets)
            out.append(OrderSource(f"stage {k + 1} mesh {h}x", h * x.params[I_Z] * abs(lay.bodies[x.a].ratio), (c,),
                                   "mesh", float(h), k + 1, phased))
    for i, b in enumerate(lay.shaft_body):
        via = planet_excitation.shaft_meshes(lay, b, [stages[j] for j in (i - 1, i) if 0 <= j < len(stages)])
        for h in SHAFT_ORDERS:
            out.append(OrderSource(f"shaft {i + 1} {h}x", h * abs(lay.bodies[b].ratio), via, "shaft", float(h), None))
    return out


@record
class TorqueSource:
    """A harmonic torque on an end body: an input ripple order (``hz_per_input_hz`` = order x the input body's
    rotation over itself, ``fixed_Hz`` None) or a load fluctuation (``fixed_Hz``, ``hz_per_input_hz`` 0)."""

    name: str
    source: str  # "input_torque_ripple" | "load_fluctuation"
    order: float  # per input revolution (ripple); 1 for a fluctuation
    hz_per_input_hz: float
    fixed_Hz: float | None
    body: int  # the body the torque acts on


def torque_sources(lay: Layout) -> list[TorqueSource]:
    """The input torque ripple's orders (at the input body, body 0) and the load fluctuation's frequencies (at
    the load body, the last one), each distinct value once."""
    out = [TorqueSource(f"input torque ripple order {n:g}", "input_torque_ripple", float(n),
                        abs(n * lay.bodies[0].ratio), None, 0)
           for n in dict.fromkeys(abs(n) for a, n in lay.drive.ripple if a != 0.0 and n != 0.0)]
    out += [TorqueSource(f"load fluctuation {f:g} Hz", "load_fluctuation", 1.0, 0.0, float(f), lay.n_bodies - 1)
            for f in dict.fromkeys(abs(f) for b, f in lay.load.fluctuation if b != 0.0 and f != 0.0)]
    return out


def _shape(v: np.ndarray) -> np.ndarray:
    j = int(np.argmax(np.abs(v)))
    return v / v[j] if v[j] != 0 else v


def modal_analysis(lay: Layout, boundary: str = "clamped_input", *, duration_s: float = 1.0) -> ModalAnalysis:
    """Modes of the chain linearised at full load (``duration_s``: the run-up for an unloaded mesh); computed once
    per layout and arguments (a run asks for them for its resonance check and again for its ringing check)."""
    if boundary not in BOUNDARIES:
        raise ValueError(f"boundary must be one of {BOUNDARIES}")
    cache = lay.__dict__.setdefault("_modal_analyses", {})
    key = (boundary, float(duration_s))
    if key not in cache:
        cache[key] = _modal_analysis(lay, boundary, duration_s)
    return cache[key]


@record
class _Undamped:
    """The undamped eigenproblem of :func:`modal_analysis`: tangent stiffness and damping per connector, the
    first free body, the speed map and inertias of the free bodies, 1/sqrt(J), the eigenpairs of the
    mass-normalised stiffness, the rigid-mode count and the modes in ascending order."""

    k: np.ndarray
    cd: np.ndarray
    first: int
    R: np.ndarray
    inv_sqrt: np.ndarray
    w2: np.ndarray
    u: np.ndarray
    n_rigid: int
    order: np.ndarray


def _undamped(lay: Layout, boundary: str, duration_s: float,
              tangents: tuple[np.ndarray, np.ndarray] | None = None) -> _Undamped:
    """:class:`_Undamped` of a layout, boundary and run-up (kept with the layout until the analysis is made);
    ``tangents``: :func:`connector_tangents` when the caller has them (:func:`resonances`)."""
    cache = lay.__dict__.setdefault("_undamped_modes", {})
    key = (boundary, float(duration_s))
    if key not in cache:
        k, cd = connector_tangents(lay, duration_s) if tangents is None else tangents
        # the eigenproblem of these very tangents on this very chain: a speed sweep's points share it
        chain = (boundary, k.tobytes(), cd.tobytes(), lay.n_bodies, tuple(lay.inertias),
                 tuple((x.bodies, x.levers, x.radii) for x in lay.connectors), loss_factors(lay).tobytes())
        found = _CHAINS.get(chain)
        cache[key] = found if found is not None else remember(_CHAINS, chain, _eigenproblem(lay, boundary, k, cd))
    return cache[key]


_CHAINS: dict[tuple, _Undamped] = {}  # _undamped by its exact tangents and chain


def _eigenproblem(lay: Layout, boundary: str, k: np.ndarray, cd: np.ndarray) -> _Undamped:
    first = 1 if boundary == "clamped_input" else 0
    R = speed_map(lay, range(first, lay.n_bodies))
    J = np.asarray(lay.inertias[first:])
    inv_sqrt = 1.0 / np.sqrt(J)
    if any(x.lossy for x in lay.connectors):
        # a lossy mesh passes eta of its force to the side that receives the power (what simulate integrates):
        # K = L^T diag(k) R is not symmetric, and the chain rings at its eigenvalues (a single mesh behind a speed
        # drive at w^2 = eta k_t r_bg^2 / J_g, not k_t r_bg^2 / J_g)
        w2, u = real_eigenpairs(inv_sqrt[:, None] * body_matrices(lay, k, cd, first)[1] * inv_sqrt[None, :])
        w2, u = orthonormal_clusters(*soft_modes_refined(R, k, J, w2, u, lever_matrices(lay, first)[1]))
    else:
        Kb = R.T @ (k[:, None] * R)
        w2, u = np.linalg.eigh(inv_sqrt[:, None] * Kb * inv_sqrt[None, :])  # mass-normalised: J^-1/2 K J^-1/2
        w2, u = soft_modes_refined(R, k, J, w2, u)
    found = _Undamped(k, cd, first, R, inv_sqrt, w2, u, rigid_mode_count(lay, k, clamped=first), np.argsort(w2))
    for a in (k, cd, R, inv_sqrt, w2, u, found.order):  # shared by the points of one chain: read only
        a.flags.writeable = False
    return found


def _modal_analysis(lay: Layout, boundary: str, duration_s: float) -> ModalAnalysis:
    und = _undamped(lay, boundary, duration_s)
    f_in = lay.drive.speed_rad_s / (2.0 * math.pi)
    phi, zetas = _damping(lay, und)
    modes = [_mode(lay, und, phi, zetas, rank, j, f_in) for rank, j in enumerate(und.order)]
    rpm = 60.0 * f_in
    return ModalAnalysis(boundary, tuple(b.label for b in lay.bodies), tuple(x.label for x in lay.connectors),
                         tuple(float(v) for v in und.k), tuple(modes), rpm, (0.0, SPEED_RANGE * rpm))


def _damping(lay: Layout, und: _Undamped, key: bytes | None = None) -> tuple[np.ndarray, np.ndarray]:
    """The body-angle shapes (mass-normalised) and every mode's damping ratio and damped frequency
    (:func:`gearcli.model.damping.modal_damping`: rows 0 and 1): kept with ``und`` (the chain's
    eigenproblem, which a speed sweep's points share: :func:`_undamped`) for the bodies' own damping by the drive
    and the load (:func:`gearcli.model.damping.body_damping`, the one input of the ratios ``und``'s chain does not
    fix: a motor's slope and a load law's at the point's speed; ``key``: its bytes where the caller has them), read
    only."""
    kept = und.__dict__.setdefault("_damping", {})
    key = body_damping(lay).tobytes() if key is None else key
    if key not in kept:
        found = _damping_of(lay, und)
        for a in found:
            a.flags.writeable = False
        remember(kept, key, found)
    return kept[key]


def _damping_of(lay: Layout, und: _Undamped) -> tuple[np.ndarray, np.ndarray]:
    phi = und.inv_sqrt[:, None] * und.u  # body-angle shapes
    order, n_rigid = und.order, und.n_rigid
    omega = np.zeros(und.w2.size)
    omega[order[n_rigid:]] = np.sqrt(np.clip(und.w2[order[n_rigid:]], 0.0, None))
    return phi, modal_damping(*body_matrices(lay, und.k, und.cd, und.first), phi, omega)


def _mode(lay: Layout, und: _Undamped, phi: np.ndarray, zetas: np.ndarray, rank: int, j: int, f_in: float,
          crossings: bool = True) -> Mode:
    """Mode ``rank`` (eigenpair ``j``) of the analysis; ``crossings=False``: without its order crossings."""
    rigid = rank < und.n_rigid  # from the structure, never from a threshold on the eigenvalues
    f = 0.0 if rigid else math.sqrt(max(float(und.w2[j]), 0.0)) / (2.0 * math.pi)
    shape = np.concatenate([np.zeros(und.first), _shape(phi[:, j])])
    rate = und.R @ phi[:, j]  # phi's scale cancels in the shares (mass-normalised for a lossless chain)
    strain = und.k * rate**2
    share = np.zeros(lay.n_conn) if rigid or strain.sum() <= 0 else strain / strain.sum()
    dominant = "" if rigid else dominant_label(lay, share)
    zeta, rings = (0.0, math.nan) if rigid else (float(zetas[0, j]), float(zetas[1, j]) / (2.0 * math.pi))
    found: tuple[Crossing, ...] = ()
    if crossings and not rigid:
        found = tuple(_crossing(o, f, _participation(und, rank, o, share), zeta) for o in excitation_sources(lay)
                      if f / o.hz_per_input_hz <= SPEED_RANGE * f_in)
        found += tuple(torque_crossing(lay, t, f, shape, zeta) for t in torque_sources(lay)
                       if meets(t, f, 60.0 * SPEED_RANGE * f_in))
    return Mode(rank + 1, f, rigid, tuple(float(v) for v in shape), tuple(float(s) for s in share), dominant,
                found, zeta, rings if math.isfinite(rings) else None)


def _crossing(o: OrderSource, f: float, s: float, zeta: float) -> Crossing:
    """Order ``o`` crossing a mode of ``f`` Hz whose participation in it is ``s`` (:func:`_participation`)."""
    return Crossing(o.name, o.hz_per_input_hz, 60.0 * f / o.hz_per_input_hz, s, s / (2.0 * zeta) if zeta > 0 else None,
                    o.source, o.order)


def order_crossing(lay: Layout, boundary: str, duration_s: float, m: Mode, o: OrderSource) -> Crossing:
    """Order ``o`` crossing mode ``m`` of the analysis (``boundary``, ``duration_s``): what ``m.crossings`` holds
    for it, at any speed (the Campbell diagram's up to its own top speed)."""
    und = _undamped(lay, boundary, duration_s)
    return _crossing(o, m.frequency_Hz, _participation(und, m.number - 1, o, m.energy_share), m.damping_ratio)


def _participation(und: _Undamped, rank: int, o: OrderSource, share: np.ndarray | tuple[float, ...]) -> float:
    """Order ``o``'s participation in mode ``rank``: a planetary stage's mesh order, its planet meshes' phased sum
    over the mode's repeated group (:func:`phased_participation`); any other order, the largest share of the mode's
    strain energy among the connectors it acts through."""
    if o.phased:
        return _phased(und, repeated_group(und, rank), o)
    return _participation_of_shares(o, share)


def repeated_group(und: _Undamped, rank: int) -> tuple[int, ...]:
    """The ranks of mode ``rank``'s repeated group (:func:`gearcli.model.planet_excitation.repeated_ranks`)."""
    return repeated_ranks(_elastic_Hz(und), und.n_rigid, rank)


def _phased(und: _Undamped, ranks: tuple[int, ...], o: OrderSource) -> float:
    """:func:`gearcli.model.planet_excitation.phased_participation` of order ``o`` in the modes ``ranks``."""
    return phased_participation(und.k, und.R, und.inv_sqrt, und.u[:, und.order[list(ranks)]], o.phased)

def near_nominal(crossing_rpm: float, nominal_rpm: float) -> bool:
    """Whether an order crossing a mode at ``crossing_rpm`` lies, at the nominal input speed, within
    ``RESONANCE_BAND`` of the mode: |f_e - f_m| / f_m with f_e / f_m = n_nominal / n_crossing, the measure of the
    ``resonance`` warning (:func:`resonances`), so the report's and the Campbell diagram's "near the nominal speed"
    name exactly the orders the warning can name (not |n_crossing / n_nominal - 1|, 10.2 % for a warned 9.3 %)."""
    return crossing_rpm > 0.0 and abs(nominal_rpm / crossing_rpm - 1.0) <= RESONANCE_BAND


def meets(t: TorqueSource, f: float, top_rpm: float) -> bool:
    """Whether torque source ``t`` crosses a mode of ``f`` Hz for input speeds 0 .. ``top_rpm``: an order below the
    top speed, a fixed frequency within ``RESONANCE_BAND`` of the mode (then at every speed)."""
    if t.fixed_Hz is not None:
        return abs(t.fixed_Hz - f) <= RESONANCE_BAND * f
    return 60.0 * f / t.hz_per_input_hz <= top_rpm


def kinetic_share(lay: Layout, shape: tuple[float, ...] | np.ndarray, body: int) -> float:
    """Body ``body``'s share J_b phi_b^2 / sum J phi^2 of the mode's kinetic energy (any scale of the shape)."""
    J = np.asarray(lay.inertias, float)
    v = np.asarray(shape, float)
    total = float(J @ v**2)
    return float(J[body] * v[body] ** 2 / total) if total > 0 else 0.0


def torque_crossing(lay: Layout, t: TorqueSource, f: float, shape: tuple[float, ...] | np.ndarray,
                     zeta: float) -> Crossing:
    p = kinetic_share(lay, shape, t.body)
    rpm = None if t.fixed_Hz is not None else 60.0 * f / t.hz_per_input_hz
    return Crossing(t.name, t.hz_per_input_hz, rpm, p, p / (2.0 * zeta) if zeta > 0 else None, t.source, t.order,
                    t.fixed_Hz)


@record
class Resonance:
    """An excitation near a natural frequency at the operating speed, with its warning's message."""

    mode: int | None  # None: a damped mode no undamped mode stands for (gearcli.model.damped_resonance)
    frequency_Hz: float
    element: str
    share: float
    excitation: str
    excitation_Hz: float
    message: str
    participation: float = 0.0  # the exciting meshes' share of the mode's strain energy
    amplification: float | None = None  # participation / (2 zeta); None: undamped
    damping_ratio: float = 0.0
    strength: str = ""  # "strongly" | "moderately"
    stage: int | None = None  # the exciting mesh's stage (None for a shaft order or a torque)
    source: str = "mesh"  # one of SOURCES

    @property
    def data(self) -> dict:
        """The diagnostic's data of this resonance (``gearcli.diagnostics.warning(RESONANCE, message, **data)``)."""
        return {"stage": self.stage, "mode": self.mode, "frequency_Hz": self.frequency_Hz,
                "excitation": self.excitation, "excitation_Hz": self.excitation_Hz, "element": self.element,
                "participation": self.participation, "amplification": self.amplification,
                "damping_ratio": self.damping_ratio, "strength": self.strength, "source": self.source}


def _percent(x: float) -> str:
    return f"{100 * x:.2g} %" if x < 0.1 else f"{100 * x:.0f} %"


def resonances(lay: Layout, boundary: str = "clamped_input", *, duration_s: float = 1.0,
               full_load: tuple[np.ndarray, np.ndarray] | None = None) -> list[Resonance]:
    """Excitations at the nominal speed within ``RESONANCE_BAND`` of a natural frequency that excite the mode
    (:attr:`Crossing.amplification` at least ``WARN_AMPLIFICATION``): mesh orders 1x-3x, shaft orders 1x, the input
    torque ripple's orders and the load fluctuation's frequencies. ``full_load``: every connector's tangent
    stiffness and damping at the static forces when the caller has them (a run's method choice linearised the
    chain there: :func:`gearcli.model.linearise` takes the same tangents), used where none of them is 0 (an unloaded
    Hertzian mesh's modes are those of the run-up load, :func:`connector_tangents`)."""
    f_in = lay.drive.speed_rad_s / (2.0 * math.pi)
    out = []
    tangents = full_load if full_load is not None and not bool(np.any(np.asarray(full_load[0]) == 0.0)) else None
    und: _Undamped | None = None  # the eigenproblem, for a planetary's phased mesh orders only
    sources = excitation_sources(lay)  # (the layout's, the same list for every mode)
    for m in _near_modes(lay, boundary, duration_s, f_in, tangents):
        if m.rigid:
            continue
        band = RESONANCE_BAND * m.frequency_Hz
        for o in (o for o in sources if not abs(o.hz_per_input_hz * f_in - m.frequency_Hz) > band):
            fe = o.hz_per_input_hz * f_in
            dominant, share, name = m.dominant, max(m.energy_share), o.name
            group: tuple[int, ...] = ()
            if o.phased:
                und = und if und is not None else _undamped(lay, boundary, duration_s, tangents)
                group = repeated_group(und, m.number - 1)
                if group[0] != m.number - 1:
                    continue  # a repeated mode is warned once, at its first mode
                s = _phased(und, group, o)
                dominant, share = planet_excitation.group_dominant(lay, und.k, und.R, und.inv_sqrt,
                                                                   und.u[:, und.order[list(group)]])
            else:
                s = _participation_of_shares(o, m.energy_share)
            c = _crossing(o, m.frequency_Hz, s, m.damping_ratio)
            if c.amplification is not None and c.amplification < WARN_AMPLIFICATION:
                continue  # the exciting mesh holds too little of the mode's strain energy to drive it
            gain = (f"resonant response ≈ {c.amplification:.2g}x its blocked error force at "
                    f"{100 * m.damping_ratio:.2g} % modal damping" if c.amplification is not None
                    else "undamped: the response grows without bound")
            named = planet_excitation.mode_name(m.number, group)
            msg = (f"resonance: the {name} order ({fe:.4g} Hz at the nominal input speed) lies within "
                   f"{100 * abs(fe - m.frequency_Hz) / m.frequency_Hz:.2g} % of {named} "
                   f"({m.frequency_Hz:.4g} Hz, {boundary}), dominated by the {dominant} "
                   f"({100 * share:.0f} % of its strain energy); {c.strength} excited: {_holder(lay, o)} "
                   f"{_percent(c.participation)} of the mode's strain energy ({gain})")
            out.append(Resonance(m.number, m.frequency_Hz, dominant, share, name, fe, msg, c.participation,
                                 c.amplification, m.damping_ratio, c.strength,
                                 o.stage, c.source))
        out += _torque_resonances(lay, m, boundary, f_in)
    from gearcli.model.damped_resonance import unmatched_resonances  # lazy: it reads this module's sources
    und = und if und is not None else _undamped(lay, boundary, duration_s, tangents)
    d = body_damping(lay).tobytes()  # with und's chain, what fixes the damped eigenvalues: their memo's key
    return out + unmatched_resonances(lay, boundary, _damping(lay, und, d)[1][1], np.sqrt(np.clip(und.w2, 0.0, None)),
                                      und.k, und.cd, und.first, f_in, und.__dict__.setdefault("_unmatched", {}), d)


def _participation_of_shares(o: OrderSource, share: np.ndarray | tuple[float, ...]) -> float:
    """An unphased order's participation: the largest share of the mode's strain energy among its connectors."""
    return float(max((share[c] for c in o.via), default=0.0))


def _holder(lay: Layout, o: OrderSource) -> str:
    """What holds the participation, in a resonance warning: "the stage 1 mesh holds"."""
    if o.phased:
        return f"the {len(o.phased)} planet meshes of stage {o.stage}, summed at their mesh phases, reach"
    via = o.via
    source = lay.connectors[via[0]].label if len(via) == 1 else "meshes of shaft " + o.name.split()[1]
    return f"the {source} holds"


def _torque_resonances(lay: Layout, m: Mode, boundary: str, f_in: float) -> list[Resonance]:
    """:func:`resonances` of the input torque ripple's orders and the load fluctuation's frequencies."""
    out = []
    share = max(m.energy_share)
    for t in torque_sources(lay):
        fe = t.fixed_Hz if t.fixed_Hz is not None else t.hz_per_input_hz * f_in
        if abs(fe - m.frequency_Hz) > RESONANCE_BAND * m.frequency_Hz:
            continue
        c = torque_crossing(lay, t, m.frequency_Hz, m.shape, m.damping_ratio)
        if c.amplification is not None and c.amplification < WARN_AMPLIFICATION:
            continue  # the excited body barely moves in the mode (near a node of it)
        body = lay.bodies[t.body].label
        gain = (f"resonant response ≈ {c.amplification:.2g}x the harmonic torque at "
                f"{100 * m.damping_ratio:.2g} % modal damping" if c.amplification is not None
                else "undamped: the response grows without bound")
        where = "at every speed" if t.fixed_Hz is not None else "at the nominal input speed"
        msg = (f"resonance: the {t.name} ({fe:.4g} Hz {where}) lies within "
               f"{100 * abs(fe - m.frequency_Hz) / m.frequency_Hz:.2g} % of mode {m.number} "
               f"({m.frequency_Hz:.4g} Hz, {boundary}), dominated by the {m.dominant} "
               f"({100 * share:.0f} % of its strain energy); {c.strength} excited: the {body}, where the torque "
               f"acts, holds {_percent(c.participation)} of the mode's kinetic energy ({gain})")
        out.append(Resonance(m.number, m.frequency_Hz, m.dominant, share, t.name, fe, msg, c.participation,
                             c.amplification, m.damping_ratio, c.strength, None, t.source))
    return out


def _near_modes(lay: Layout, boundary: str, duration_s: float, f_in: float,
                tangents: tuple[np.ndarray, np.ndarray] | None = None) -> list[Mode]:
    """The modes an order at the nominal speed may lie near (:func:`resonances` passes over the others): the
    analysis's where it is made; else only the elastic modes within ``RESONANCE_BAND`` of an order, without their
    crossings (the same numbers: the analysis's own steps, :func:`_mode`)."""
    ana = lay.__dict__.get("_modal_analyses", {}).get((boundary, float(duration_s)))
    if ana is not None:
        return list(ana.modes)
    und = _undamped(lay, boundary, duration_s, tangents)
    fe = [o.hz_per_input_hz * f_in for o in excitation_sources(lay)]
    fe += [t.fixed_Hz if t.fixed_Hz is not None else t.hz_per_input_hz * f_in for t in torque_sources(lay)]
    near = [(rank, j) for rank, (j, f) in enumerate(_elastic_Hz(und)) if rank >= und.n_rigid
            and any(not abs(x - f) > RESONANCE_BAND * f for x in fe)]
    if not near:
        return []  # no order near a mode: no shapes, shares nor damping to work out
    damping = body_damping(lay).tobytes()
    phi, zetas = _damping(lay, und, damping)
    # a mode without its crossings reads no speed: the chain's (und), its damping and the connectors' names fix it
    kept = und.__dict__.setdefault("_near_modes", {})
    labels = tuple(x.label for x in lay.connectors)
    out = []
    for rank, j in near:
        key = (damping, labels, rank, j)
        found = kept.get(key)
        out.append(found if found is not None else remember(kept, key, _mode(lay, und, phi, zetas, rank, j, f_in,
                                                                             crossings=False), cap=64))
    return out


def _elastic_Hz(und: _Undamped) -> list[tuple[int, float]]:
    """(eigenpair, :func:`_frequency_Hz`) in ascending order (``und.order``), once per chain (its points share it)."""
    kept = und.__dict__.get("_hz")
    if kept is None:
        kept = [(int(j), _frequency_Hz(und, int(j))) for j in und.order]
        und.__dict__["_hz"] = kept
    return kept


def _frequency_Hz(und: _Undamped, j: int) -> float:
    return math.sqrt(max(float(und.w2[j]), 0.0)) / (2.0 * math.pi)


def campbell_data(lay: Layout, boundary: str = "clamped_input", *, duration_s: float = 1.0,
                  max_input_rpm: float | None = None) -> CampbellData:
    """The Campbell diagram of the chain up to ``max_input_rpm`` (default ``SPEED_RANGE`` x nominal)."""
    from gearcli.model.campbell import campbell_of  # lazy: a diagram only

    return campbell_of(lay, boundary, duration_s=duration_s, max_input_rpm=max_input_rpm)

#: the Campbell diagram's types (:mod:`gearcli.model.campbell`), imported on first use by this module's name too
CAMPBELL = ("CampbellCrossing", "CampbellData")


def __getattr__(name: str) -> object:
    if name in CAMPBELL:  # PEP 562
        from gearcli.model import campbell  # lazy: a run that draws no Campbell diagram never creates its classes

        return getattr(campbell, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
