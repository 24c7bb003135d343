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
and the mesh orders (1x and 2x each stage's mesh frequency) that cross it while the input body runs
from 0 to ``SPEED_RANGE`` x its nominal speed.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from gearcli.model.assembly import Layout
from gearcli.model.elements.mesh import I_Z
from gearcli.model.linear import peak_rigid_forces, speed_map, static_forces, tangent

SPEED_RANGE = 1.2  # operating range: 0 .. 1.2 x the nominal input speed
MESH_ORDERS = (1, 2)  # harmonics of each stage's mesh frequency
RIGID_TOL = 1e-9  # omega^2 below this x the largest: a rigid-body mode
RESONANCE_BAND = 0.10  # |f_excitation - f_mode| / f_mode that the simulation warns about
BOUNDARIES = ("clamped_input", "free")


@dataclass(frozen=True)
class Crossing:
    excitation: str  # "stage 1 mesh 1x"
    hz_per_input_hz: float  # excitation frequency over the input body's rotation frequency
    input_speed_rpm: float  # input body speed at which it meets the mode


@dataclass(frozen=True)
class Mode:
    number: int  # 1-based, ascending frequency
    frequency_Hz: float
    rigid: bool
    shape: tuple[float, ...]  # per body
    energy_share: tuple[float, ...]  # per connector; all 0 for a rigid mode
    dominant: str  # label of the connector with the largest share ("" for a rigid mode)
    crossings: tuple[Crossing, ...]


@dataclass(frozen=True)
class ModalAnalysis:
    boundary: str
    bodies: tuple[str, ...]
    connectors: tuple[str, ...]
    stiffness: tuple[float, ...]  # tangent stiffness per connector (N/m or N m/rad)
    modes: tuple[Mode, ...]
    nominal_input_rpm: float
    speed_range_rpm: tuple[float, float]


def _stiffness(lay: Layout, duration_s: float) -> np.ndarray:
    F = static_forces(lay)
    k = np.array([tangent(lay, c, F[c])[0] for c in range(lay.n_conn)])
    if np.any(k == 0.0):  # an unloaded Hertzian mesh: the run-up load, stiffest phase (as the simulation)
        op = np.maximum(np.abs(F), peak_rigid_forces(lay, duration_s))
        k = np.array([tangent(lay, c, op[c], stiffest_phase=True)[0] for c in range(lay.n_conn)])
    return k


def excitations(lay: Layout) -> list[tuple[str, float]]:
    """(name, frequency over the input body's rotation frequency) of the mesh orders."""
    out = []
    for k, c in enumerate(lay.stage_conn):
        x = lay.connectors[c]
        for h in MESH_ORDERS:
            out.append((f"stage {k + 1} mesh {h}x", h * x.params[I_Z] * abs(lay.bodies[x.a].ratio)))
    return out


def _shape(v: np.ndarray) -> np.ndarray:
    j = int(np.argmax(np.abs(v)))
    return v / v[j] if v[j] != 0 else v


def modal_analysis(lay: Layout, boundary: str = "clamped_input", *, duration_s: float = 1.0) -> ModalAnalysis:
    """Modes of the chain linearised at full load (``duration_s``: the run-up for an unloaded mesh)."""
    if boundary not in BOUNDARIES:
        raise ValueError(f"boundary must be one of {BOUNDARIES}")
    k = _stiffness(lay, duration_s)
    first = 1 if boundary == "clamped_input" else 0
    R = speed_map(lay, range(first, lay.n_bodies))
    J = np.asarray(lay.inertias[first:])
    inv_sqrt = 1.0 / np.sqrt(J)
    Kb = R.T @ (k[:, None] * R)
    w2, u = np.linalg.eigh(inv_sqrt[:, None] * Kb * inv_sqrt[None, :])
    phi = inv_sqrt[:, None] * u  # body-angle shapes
    f_in = lay.drive.speed_rad_s / (2.0 * math.pi)
    top = max(float(np.max(np.abs(w2))), np.finfo(float).tiny)
    modes: list[Mode] = []
    for j in np.argsort(w2):
        rigid = bool(w2[j] <= RIGID_TOL * top)
        f = 0.0 if rigid else math.sqrt(w2[j]) / (2.0 * math.pi)
        shape = np.concatenate([np.zeros(first), _shape(phi[:, j])])
        strain = k * (R @ phi[:, j]) ** 2
        share = np.zeros(lay.n_conn) if rigid or strain.sum() <= 0 else strain / strain.sum()
        dominant = "" if rigid else lay.connectors[int(np.argmax(share))].label
        crossings = tuple(Crossing(name, r, 60.0 * f / r) for name, r in excitations(lay)
                          if not rigid and f / r <= SPEED_RANGE * f_in)
        modes.append(Mode(len(modes) + 1, f, rigid, tuple(float(v) for v in shape),
                          tuple(float(s) for s in share), dominant, crossings))
    rpm = 60.0 * f_in
    return ModalAnalysis(boundary, tuple(b.label for b in lay.bodies), tuple(x.label for x in lay.connectors),
                         tuple(float(v) for v in k), tuple(modes), rpm, (0.0, SPEED_RANGE * rpm))


@dataclass(frozen=True)
class Resonance:
    mode: int
    frequency_Hz: float
    element: str
    share: float
    excitation: str
    excitation_Hz: float
    message: str


def resonances(lay: Layout, boundary: str = "clamped_input", *, duration_s: float = 1.0) -> list[Resonance]:
    """Mesh orders at the nominal speed within ``RESONANCE_BAND`` of a natural frequency."""
    ana = modal_analysis(lay, boundary, duration_s=duration_s)
    f_in = lay.drive.speed_rad_s / (2.0 * math.pi)
    out = []
    for m in ana.modes:
        if m.rigid:
            continue
        share = max(m.energy_share)
        for name, r in excitations(lay):
            fe = r * f_in
            if abs(fe - m.frequency_Hz) <= RESONANCE_BAND * m.frequency_Hz:
                msg = (f"resonance: the {name} order ({fe:.4g} Hz at the nominal input speed) lies within "
                       f"{100 * abs(fe - m.frequency_Hz) / m.frequency_Hz:.2g} % of mode {m.number} "
                       f"({m.frequency_Hz:.4g} Hz, {boundary}), dominated by the {m.dominant} "
                       f"({100 * share:.0f} % of its strain energy)")
                out.append(Resonance(m.number, m.frequency_Hz, m.dominant, share, name, fe, msg))
    return out
