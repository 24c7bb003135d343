"""Natural frequencies against the swept input speed, for the Campbell diagram.

:func:`natural_frequencies_Hz` is the one call to the modes capability (the undamped
frequencies of ``gearcli modes``). Mesh-order lines: stage s meshes at ``z_p,s n_s / 60`` Hz with ``n_s`` its pinion's rpm.
The points are loaded and designed by the injected ``design_case`` (the facade's :func:`gearcli.api.design_case`).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import cast

from gearcli.config import DesignFile
from gearcli.core.jsontypes import JsonScalar
from gearcli.core.records import record
from gearcli.errors import GearcliError
from gearcli.model.assembly import Layout
from gearcli.model.campbell import CampbellData
from gearcli.model.modes import SPEED_RANGE, campbell_data, modal_analysis
from gearcli.results import DesignResult
from gearcli.scene import spec_from_design
from gearcli.stages.design import design_kind
from gearcli.sweep.spec import SPEED_KEYS, Axis, SweepSpec, toml_value
from gearcli.sweep.worker import CaseDesigner, Scene

SAMPLES_TRIED = 64  # the --random samples tried for one that designs (each a design: a study of 1e6 stays quick)
UnitsOf = Callable[[DesignFile], tuple[str, str]]  # a file's output units (io.units.key_units, injected by the facade)



def natural_frequencies_Hz(cfg: DesignFile, design: DesignResult) -> tuple[float, ...]:
    """The modes capability's frequencies (``gearcli modes``) at the boundary the drive imposes: a speed
    drive holds the input body (``clamped_input``), a torque drive leaves the chain ``free``; the rigid
    mode (0 Hz) left out."""
    lay = Layout.of(spec_from_design(cfg, design))
    boundary = "clamped_input" if lay.speed_drive else "free"
    analysis = modal_analysis(lay, boundary, duration_s=cfg.simulation.duration_s)
    return tuple(float(m.frequency_Hz) for m in analysis.modes if not m.rigid)


@record
class CampbellPoint:
    input_rpm: float
    natural_Hz: tuple[float, ...]
    mesh_Hz: tuple[float, ...]  # first-order mesh frequency of each stage (0: a plug-in kind without a gear mesh)
    value: JsonScalar = None  # the swept key's value (in its own unit)


@record
class SweepCampbell:
    """The Campbell diagram of a speed sweep: the data, the swept input speeds (rpm), and the output units
    (speed and torque key suffixes) of the swept key."""

    data: CampbellData
    swept_rpm: tuple[float, ...]
    units: tuple[str, str]
    at: tuple[str, ...] = ()  # the other swept keys' values it is drawn at (``load.torque_Nm=300``), named in its title


def _number(value: JsonScalar) -> float:
    return float(cast(float, value))  # a speed axis holds numbers


def _speed_point(key: str, value: JsonScalar) -> str:
    return f"{key}={_number(value)!r}"


def _input_rpm(design: DesignResult) -> float:
    """The input member's speed: the drive's, not the first stage's pinion's (a planetary first stage's "pinion" is
    its sun, whose speed there is the mesh's, relative to the carrier: 1125 rpm of a sun driven at 1500 rpm, 900 rpm
    of a carrier's 300; the Campbell diagram marked the swept speeds there and ran its axis to them)."""
    return design.input_speed_deg_s / 6.0


def campbell(scene: Scene, key: str, values: Sequence[JsonScalar], design_case: CaseDesigner,
             fixed: Sequence[str] = ()) -> list[CampbellPoint]:
    """Natural and mesh frequencies at each swept input speed that designs (the other keys at ``fixed``
    overrides); a speed the design file's bounds refuse is left out, as its row is a failed one."""
    out = []
    for v in values:
        try:
            cfg, design = design_case(scene, (*fixed, _speed_point(key, v)))
        except GearcliError:  # a speed whose row failed (0 rpm, beyond the bounds): no modes there
            continue
        mesh = tuple(st.pinion.teeth * st.pinion.speed_rpm / 60.0 if design_kind(st).gear_pair else 0.0
                     for st in design.stages)
        out.append(CampbellPoint(_input_rpm(design), natural_frequencies_Hz(cfg, design), mesh, v))
    return out


def campbell_diagram(scene: Scene, key: str, values: Sequence[JsonScalar], design_case: CaseDesigner,
                     units_of: UnitsOf, fixed: Sequence[str] = ()) -> SweepCampbell | None:
    """The modes and order lines of the scene at the file's own speed (the other keys at ``fixed``), over the
    swept range (a sweep of one speed: 0 .. the larger of 1.2 x the file's speed and that one): the same drawing
    as ``gearcli modes --plots``, with the swept speeds."""
    points = campbell(scene, key, values, design_case, fixed)
    swept = [p.input_rpm for p in points]
    if not points:  # every swept speed failed: no diagram
        return None
    cfg, design = design_case(scene, tuple(fixed))
    lay = Layout.of(spec_from_design(cfg, design))
    nominal = _input_rpm(design)
    data = campbell_data(lay, "clamped_input" if lay.speed_drive else "free", duration_s=cfg.simulation.duration_s,
                         max_input_rpm=max(swept) if min(swept) < max(swept) else max([SPEED_RANGE * nominal, *swept]))
    units = units_of(design_case(scene, (*fixed, _speed_point(key, points[0].value))).cfg)  # the swept key's unit
    return SweepCampbell(data, tuple(swept), units, tuple(fixed))


def speed_axis(spec: SweepSpec) -> Axis | None:
    """The swept input speed, if any."""
    return next((a for a in spec.axes if a.key in SPEED_KEYS), None)


def sweep_campbell(spec: SweepSpec, scene: Scene, design_case: CaseDesigner, units_of: UnitsOf) -> SweepCampbell | None:
    """``gearcli sweep --plots``: the Campbell diagram over the swept input speed (each other axis at its first
    value that designs, the ``--random`` keys at their first sample that designs: a point the rows ran at, named in
    the title, not the file's values, which no sample need hold); None when no input speed is swept, or none designs."""
    axis = speed_axis(spec)
    if axis is None:
        return None
    fixed: list[str] = []
    for other in (a for a in spec.axes if a.key != axis.key):  # its first value that designs (a failed row's not)
        sets = [f"{other.column}={toml_value(v)}" for v in other.values]  # as written: named in the title
        fixed.append(next((s for s in sets if _designs(scene, design_case, (*fixed, s))), sets[0]))
    if spec.randoms:  # the --random keys at their first sample that designs (drawn together: one sample's values)
        drawn = [[f"{d.column}={toml_value(v)}" for d, v in zip(spec.randoms, sample, strict=True)]
                 for sample in spec.random_values()[:SAMPLES_TRIED]]
        fixed += next((s for s in drawn if _designs(scene, design_case, (*fixed, *s))), drawn[0])
    # a value that is no number (``--vary input.speed_rpm=1000,fast``) is no speed: its row failed, no modes there
    speeds = sorted((v for v in axis.values if isinstance(v, (int, float)) and not isinstance(v, bool)), key=_number)
    return campbell_diagram(scene, axis.key, speeds, design_case, units_of, fixed) if speeds else None


def _designs(scene: Scene, design_case: CaseDesigner, overrides: Sequence[str]) -> bool:
    try:
        design_case(scene, tuple(overrides))
    except GearcliError:
        return False
    return True
