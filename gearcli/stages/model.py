"""The model facet of a stage kind (the model layer, beside ``gearcli.scene``): the stage's mesh law as the
model signs it and its own model (bodies and connectors), or none where the stage is the chain's pair.

``gearcli.scene`` asks :func:`model_kind` for each designed stage; ``gearcli.model.assembly`` places a stage
model it is given (``ModelSpec.stage_models``) through its ``place``, and never asks which kind it is.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Protocol, cast

from gearcli.core import plugins
from gearcli.errors import PLUGIN_FAULTS, GearcliError, PluginError
from gearcli.model import elements
from gearcli.model.parts import Body, Connector
from gearcli.model.spec import MeshSpec, StageModel
from gearcli.results import StageResult
from gearcli.stages import kinds

if TYPE_CHECKING:
    from gearcli.config.schema import DesignFile


#: the design -> model adapter's mesh law of a gear pair: (design file, stage result, k) -> MeshSpec
PairMesh = Callable[["DesignFile", StageResult, int], MeshSpec]


class ModelKind(Protocol):
    """What the design -> model adapter (``gearcli.scene``) asks of a stage kind."""

    def line(self, cfg: DesignFile, st: StageResult, k: int, pair_mesh: PairMesh) -> MeshSpec:
        """The stage's line of action as the model reads it (``ModelSpec.meshes[k]``: its levers, its angles, its
        static force signed as the model's): a gear pair's mesh law (``pair_mesh``), a belt's span."""

    def stage_model(self, cfg: DesignFile, st: StageResult, k: int, mesh: MeshSpec) -> StageModel | None:
        """The stage's own model (SI), or None: the chain's pair of ``mesh``."""


def model_kind(stage: object) -> ModelKind:
    """The model facet of a stage table or stage result (by its ``type``)."""
    return cast(ModelKind, kinds.facet(kinds.kind_of(stage), "model"))


def checked_line_losses(st: StageResult, k: int, line: MeshSpec, own: StageModel | None) -> StageModel | None:
    """:func:`checked_losses`, and for a plug-in kind without a stage model of its own (``stage_model`` None: the
    stage is placed as the chain's pair of its ``line``) a line whose ``efficiency`` is its design's, or a
    :class:`~gearcli.errors.PluginError` naming the kind: the pair loses only its line's efficiency, so a line left
    at 1 ran a lossy stage lossless (the simulated forces before the stage eta x the design's, silently)."""
    facet = kinds.facet(kinds.kind_of(st), "model")
    origin = str(getattr(facet, "origin", plugins.origin(facet)))
    if own is None and origin.split(".")[0] != "gearcli":
        design_eta = float(getattr(st, "efficiency", 1.0))
        if not math.isclose(line.efficiency, design_eta, rel_tol=1e-9, abs_tol=1e-12):
            raise PluginError(f'stage type "{kinds.kind_of(st)}" ({origin}): its stage model is None, so stage '
                              f"{k + 1} is placed as a pair of its line, whose efficiency {line.efficiency:.6g} is not "
                              f"its design's {design_eta:.6g}: the simulated forces before it would be "
                              f"{design_eta / line.efficiency:.6g} x the design's; give its line MeshSpec.efficiency "
                              "= the design's (docs/plugins.md, \"Losses\")")
    return checked_losses(st, k, own)


def checked_losses(st: StageResult, k: int, own: StageModel | None) -> StageModel | None:
    """A plug-in's stage model ``own`` of stage ``st`` (0-based ``k``) whose losses are its design's, or a
    :class:`~gearcli.errors.PluginError` naming the kind. The dynamics lose only what a connector's element loses
    (a lossy element: the built-in ``mesh`` with ``MeshSpec.efficiency``); a stage model's own ``efficiency`` acts
    only through a planetary's planet meshes (connectors with a ``load_body``), and the steady-state and rigid-start
    estimates read it (:meth:`gearcli.model.assembly.Layout.train_efficiency`). So a stage model that places no
    planet mesh must give ``efficiency`` and ``reverse_efficiency`` 1, and its connectors must lose the design's
    (1 - eta): else the simulated forces before the stage are eta x the design's (docs/plugins.md)."""
    if own is None or plugins.origin(own).split(".")[0] == "gearcli":
        return own
    where = f'stage type "{kinds.kind_of(st)}" ({plugins.origin(own)}): its stage model'
    bodies: list[Body] = [Body(1.0, "input", 1.0)]
    conns: list[Connector] = []

    def body(inertia: float, label: str, ratio: float = 1.0) -> None:
        bodies.append(Body(float(inertia), label, ratio))

    try:
        own.place(k, bodies, conns, body, 1.0)
        if any(c.load_body >= 0 for c in conns):
            return own
        eta = math.prod(c.efficiency for c in conns if c.lossy)
        given = {n: float(getattr(own, n)) for n in ("efficiency", "reverse_efficiency")}
    except GearcliError:
        raise
    except PLUGIN_FAULTS as exc:  # third-party code: named, with what it raised
        raise PluginError(f"{where}'s place raised {type(exc).__name__}: {' '.join(str(exc).split())[:300]}") \
            from exc
    design_eta = float(getattr(st, "efficiency", 1.0))
    for name, value in given.items():
        if value != 1.0:
            raise PluginError(f"{where} gives {name} = {value:.6g}, which no element of it loses: the dynamics "
                              "lose only what its connectors' elements lose; give the model 1 and place a lossy "
                              "element (the built-in mesh with MeshSpec.efficiency; docs/plugins.md)")
    if not math.isclose(eta, design_eta, rel_tol=1e-9, abs_tol=1e-12):
        raise PluginError(f"{where}'s connectors lose {1.0 - eta:.6g} of the power, its design {1.0 - design_eta:.6g} "
                          f"(efficiency {design_eta:.6g}): the simulated forces before stage {k + 1} would be "
                          f"{design_eta / eta:.6g} x the design's (T_in = T_out / (i eta)); place a lossy element of "
                          "the design's efficiency (the built-in mesh with MeshSpec.efficiency; docs/plugins.md)")
    return own


@dataclass(frozen=True)
class LineStage:
    """A stage of a kind that is no gear pair and has no model of its own (``stage_model`` None): its line placed
    as the chain's pair, the built-in ``mesh`` element between its input body and a new body, as the stage's
    connector of role ``"stage"`` (ARCHITECTURE.md: a mesh's role is a gear mesh's). As role ``"mesh"`` the stage
    had a gear pair's mesh orders at its line's ``pinion_teeth`` (20 by default) in ``modes`` and the resonance
    warnings of ``design`` and ``simulate``, for a belt or a chain drive placed so that has no teeth meshing."""

    line: MeshSpec
    efficiency: float = 1.0  # its losses are its connector's (MeshSpec.efficiency)
    reverse_efficiency: float = 1.0

    def place(self, k: int, bodies: list[Body], conns: list[Connector], body: Callable[..., None],
              out_inertia: float) -> None:
        kind = elements.kind_of("mesh")
        n, m = len(bodies), self.line
        conns.append(Connector(kind, (n - 1, n), (m.base_radius_pinion_m, m.base_radius_gear_m),
                               tuple(float(v) for v in elements.law_of(kind).pack(m)),
                               f"stage {k + 1} {m.law or 'line'}", k, "stage"))
        body(out_inertia, f"shaft {k + 2}")


def placed(line: MeshSpec, own: StageModel | None, gear_pair: bool) -> StageModel | None:
    """A stage's model (its kind's ``own``, checked): a kind that is no gear pair and gives none is
    its :class:`LineStage` (its line as the stage's connector, no gear mesh); a gear pair's None stays the pair."""
    return LineStage(line) if own is None and not gear_pair else own


class ParallelModel:
    """A parallel stage is the chain's pair: its mesh between its input and output shafts' bodies."""

    def line(self, cfg: DesignFile, st: StageResult, k: int, pair_mesh: PairMesh) -> MeshSpec:
        return pair_mesh(cfg, st, k)

    def stage_model(self, cfg: DesignFile, st: StageResult, k: int, mesh: MeshSpec) -> StageModel | None:
        return None


class PlanetaryModelKind:
    """A planetary stage: the sun–planet mesh law signed by the output member's moment balance, and its
    :class:`~gearcli.stages.planetary_model.PlanetaryModel` (levers from the base radii, the members' inertias, both mesh laws)."""

    def line(self, cfg: DesignFile, st: StageResult, k: int, pair_mesh: PairMesh) -> MeshSpec:
        """The sun–planet mesh law with a planet mesh's static F_t signed as its deflection is in the model: the
        moment balance of the output member, N c_out F = T_out sign(w_out), c_out = -r_bs (sun), r_bs + r_br
        (carrier), -r_br (ring) (:func:`gearcli.model.planet_assembly.place_planetary`)."""
        from gearcli.design.planetary_balance import willis_speeds  # lazy: planetary stages only

        mesh = pair_mesh(cfg, st, k)
        p = st.planetary
        assert p is not None
        sign_out = 1.0 if willis_speeds(p.sun.teeth, p.ring.teeth, p.fixed, p.input)[p.output] >= 0 else -1.0
        sign = sign_out * (1.0 if p.output == "carrier" else -1.0)
        return replace(mesh, static_tangential_N=sign * mesh.static_tangential_N)

    def stage_model(self, cfg: DesignFile, st: StageResult, k: int, mesh: MeshSpec) -> StageModel | None:
        from gearcli.stages.planetary_model import planetary_model  # lazy: a file without planetary stages

        return planetary_model(cfg, st, k, mesh)


kinds.provide(kinds.PARALLEL, "model", ParallelModel())
kinds.provide("planetary", "model", PlanetaryModelKind())
