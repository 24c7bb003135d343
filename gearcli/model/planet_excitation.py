"""A planetary stage's mesh orders against the chain's modes (:mod:`gearcli.model.modes`): every planet mesh at its
own mesh phase, and a repeated mode as one eigenspace.

A mesh order of a planetary stage acts through all its planet meshes at once, each with the error
e exp(2 pi i p_c), p_c its phase at this harmonic: h z_s psi_j / 2 pi for planet j's sun mesh, -h z_r psi_j / 2 pi for
its ring mesh, the phases the model shifts their transmission error by (Parker & Lin, J. Mech. Des. 126, 2004;
:meth:`gearcli.model.planet_spec.PlanetarySpec.mesh_phase_cycles`). On a mass-normalised shape phi the modal force
is e P, P = sum_c k_c (R phi)_c exp(2 pi i p_c), and the order's participation |P|^2 / (K omega^2), K = sum_c k_c
the planet meshes' stiffness and omega^2 = sum k (R phi)^2 the mode's strain energy: a single mesh's share
k_c (R phi)_c^2 / omega^2 where there is one mesh, the meshes' summed shares where all mesh in phase, never more
than that (Cauchy-Schwarz), and 0 where the phases cancel. In-phase meshing (h z_s / N an integer) so drives only
the rotational modes; sequential meshing only the planet modes (the N - 1 repeated modes in which the central
members stand still): sum_j a_j exp(2 pi i h z_s j / N) vanishes for a_j equal (rotational) when h z_s / N is no
integer, and for sum_j a_j = 0 (planet) when it is.

A repeated mode (frequencies equal within ``REPEATED``): the solver returns any basis of its eigenspace, and a
basis vector's |P|^2 depends on which. The group's participation is the sum of |P|^2 over an orthonormal basis
(the squared projection of the modal force on the eigenspace) over K times the basis's mean strain energy: the
same for every basis.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, cast

import numpy as np

if TYPE_CHECKING:
    from gearcli.model.assembly import Layout
    from gearcli.model.planet_spec import PlanetarySpec

REPEATED = 1e-6  # modes whose frequencies differ by less than this fraction are one repeated mode (a group)
CANCELLED = 1e-9  # a phased sum below this fraction of its terms' magnitudes is their cancellation's round-off: 0


def planet_phases(lay: Layout) -> tuple[tuple[int, int, float], ...]:
    """(stage, connector, mesh phase in cycles at the mesh frequency) of every planet mesh of the layout: between
    planets Parker & Lin's, and a ring mesh's against its own planet's sun mesh (``ring_contact_phase_cycles``, the
    contact-line phase the model's contact lines, error and stiffness harmonics take). Without the latter the planet modes would be
    driven by no order at all: a planet's two meshes in phase push it equally both ways."""
    models = lay.spec.stage_models
    out = []
    for c, x in enumerate(lay.connectors):
        own = models[x.index] if x.planet >= 0 and 0 <= x.index < len(models) else None
        if own is not None:
            p = cast("PlanetarySpec", own)
            within = p.ring_contact_phase_cycles if x.gear == "ring" else 0.0
            out.append((x.index, c, float(p.mesh_phase_cycles(x.planet, x.gear) + within)))
    return tuple(out)


def shaft_meshes(lay: Layout, body: int, stage_connectors: list[int]) -> tuple[int, ...]:
    """The meshes a shaft order of ``body`` acts through (the meshes of the gears its shaft carries), from the stages
    on either side of it (``stage_connectors``: each stage's connector, :attr:`Layout.stage_conn`): a parallel stage's
    mesh; of a planetary stage, whose connector is planet 1's sun mesh, every planet mesh with a lever on ``body``
    (a sun's sun meshes, a ring's ring meshes, a carrier's all of them)."""
    out: list[int] = []
    for c in stage_connectors:
        x = lay.connectors[c]
        if x.planet < 0:
            out.append(c)
            continue
        out += [m for m, y in enumerate(lay.connectors) if y.planet >= 0 and y.index == x.index
                and any(b == body and lever != 0.0 for b, lever in zip(y.bodies, y.levers, strict=True))]
    return tuple(out)


def repeated_ranks(hz: list[tuple[int, float]], n_rigid: int, rank: int) -> tuple[int, ...]:
    """The ranks of the elastic modes (``hz``: (eigenpair, Hz) in ascending order, the first ``n_rigid`` rigid)
    whose frequency equals mode ``rank``'s within ``REPEATED``: one repeated mode."""
    f = hz[rank][1]
    return tuple(r for r, (_, g) in enumerate(hz) if r >= n_rigid and abs(g - f) <= REPEATED * f)


def phased_participation(k: np.ndarray, R: np.ndarray, inv_sqrt: np.ndarray, u: np.ndarray,
                         phased: tuple[tuple[int, float], ...]) -> float:
    """The participation (module text) of the meshes ``phased`` ((connector, phase in cycles) each) in the
    eigenspace spanned by the mass-weighted eigenvectors ``u`` (columns; any basis) of the chain with tangent
    stiffness ``k``, speed map ``R`` over the free bodies and their 1/sqrt(J) ``inv_sqrt``."""
    cs = [c for c, _ in phased]
    total = float(k[cs].sum())
    if total <= 0.0:
        return 0.0
    turn = np.exp(2j * math.pi * np.array([p for _, p in phased]))
    basis = np.linalg.qr(u)[0]  # orthonormal: mass-orthonormal shapes
    terms = (basis.T @ (inv_sqrt[:, None] * (k[cs][:, None] * R[cs]).T))  # mode x mesh: k_c (R phi)_c, mass-weighted
    projected = terms @ turn  # sum_c k_c (R phi)_c e^(2 pi i p_c) per basis mode
    # phases that cancel (cyclic symmetry) leave the round-off of the sum, ~1e-16 of its terms: that is 0, not an
    # excitation of 1e-30 (a Campbell crossing listed at "2e-28 %")
    projected[np.abs(projected) <= CANCELLED * np.abs(terms).sum(axis=1)] = 0.0
    strain = k @ (R @ (inv_sqrt[:, None] * basis)) ** 2
    mean = float(strain.mean())
    return float(np.sum(np.abs(projected) ** 2) / (total * mean)) if mean > 0.0 else 0.0


TIED = 1e-9  # strain-energy shares within this fraction of the largest are equal (a symmetric mode's round-off)


def dominant_label(lay: Layout, share: np.ndarray) -> str:
    """The element with the largest share of a mode's strain energy: a connector's label, or, where planet meshes of
    one stage hold equal largest shares (a symmetric mode: which one round-off puts first is arbitrary), all of them,
    "stage 1 planets 1, 2, 3 sun meshes", "stage 1 planet 2 sun and ring meshes"; other ties name the first."""
    top = float(np.max(share))
    tied = [lay.connectors[c] for c in range(len(share)) if share[c] >= top * (1.0 - TIED)]
    planets = sorted({x.planet for x in tied})
    gears = [g for g in ("sun", "ring") if any(x.gear == g for x in tied)]
    if (len(tied) == 1 or min(planets) < 0 or len({x.index for x in tied}) != 1
            or len(tied) != len(planets) * len(gears)):  # not every planet's every tied mesh: no one name
        return tied[0].label
    return (f"stage {tied[0].index + 1} planet{'s' if len(planets) > 1 else ''} "
            f"{', '.join(str(j + 1) for j in planets)} {' and '.join(gears)} meshes")


def group_dominant(lay: Layout, k: np.ndarray, R: np.ndarray, inv_sqrt: np.ndarray, u: np.ndarray) -> tuple[str, float]:
    """The element holding the largest share of a repeated mode's strain energy, and that share, over its
    eigenspace (``u``: its mass-weighted eigenvectors, any basis; ``k``, ``R``, ``inv_sqrt`` as
    :func:`phased_participation`): each connector's strain energy summed over an orthonormal basis is the same for
    every basis, so identical planets hold equal shares and are named together ("stage 1 planets 1, 2, 3, 4, 5 ring
    meshes"), where one basis vector's shares name whichever planet the eigensolver's basis happens to favour."""
    basis = np.linalg.qr(u)[0]
    strain = (k[:, None] * (R @ (inv_sqrt[:, None] * basis)) ** 2).sum(axis=1)
    share = strain / strain.sum()
    return dominant_label(lay, share), float(share.max())


def mode_name(number: int, group: tuple[int, ...]) -> str:
    """"mode 4", or a repeated mode's "modes 4-5 (repeated)"."""
    return f"modes {group[0] + 1}-{group[-1] + 1} (repeated)" if len(group) > 1 else f"mode {number}"
