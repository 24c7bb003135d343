"""``gearcli modes`` output: JSON document, CSV rows, rich tables (the only place that formats modes)."""

from __future__ import annotations

from rich.console import RenderableType

from gearcli.core.jsontypes import JsonObject, JsonScalar
from gearcli.core.text import figure
from gearcli.diagnostics import warning_objects
from gearcli.io.serialize import as_object, csv_text, plain
from gearcli.io.units import OutputUnits
from gearcli.model.modes import ModalAnalysis
from gearcli.results import DesignResult
from gearcli.stages.design import design_kind


def modes_document(analyses: list[ModalAnalysis], design: DesignResult) -> JsonObject:
    """``gearcli modes --format json``: :func:`modes_dict` with the design's warnings as objects and, per mesh, the
    contact law the modes are linearised from beside ISO's stiffness (``meshes[i].mesh_stiffness``)."""
    doc = modes_dict(analyses, warning_objects(design.warnings, design.diagnostics))
    warnings = doc.pop("warnings")
    return {**doc, "meshes": mesh_stiffness_rows(design), "warnings": warnings}


def mesh_stiffness_rows(design: DesignResult) -> list[JsonObject]:
    """Per mesh: its stage (1-based), which mesh (``mesh``; a planetary stage's ``sun_planet``, ``planet_ring``)
    and its ``mesh_stiffness`` {law, K, exponent, linearised_N_mm, iso_N_mm, ...}."""
    rows: list[JsonObject] = []
    for st in design.stages:
        meshes = design_kind(st).meshes(st)
        rows += [{"stage": st.index, "mesh": name, "mesh_stiffness": as_object(plain(law))}
                 for name, law in meshes if law is not None]
    return rows


def modes_dict(analyses: list[ModalAnalysis], warnings: list[JsonObject] | None = None) -> JsonObject:
    """Both boundaries; per mode its frequency, shape per body, strain-energy share per element and the
    mesh orders that cross it in the operating range."""
    first = analyses[0]
    return {
        "bodies": list(first.bodies),
        "elements": list(first.connectors),
        "element_stiffness": list(first.stiffness),
        "nominal_input_speed_rpm": first.nominal_input_rpm,
        "speed_range_rpm": list(first.speed_range_rpm),
        "boundaries": {a.boundary: [{
            "mode": m.number, "frequency_Hz": m.frequency_Hz, "rigid": m.rigid,
            "dominant_element": m.dominant,
            "shape": dict(zip(a.bodies, m.shape, strict=True)),
            "energy_share": dict(zip(a.connectors, m.energy_share, strict=True)),
            "damping_ratio": m.damping_ratio, "damped_frequency_Hz": m.damped_frequency_Hz,
            "crossings": [{"excitation": c.excitation, "input_speed_rpm": c.input_speed_rpm,
                           "participation": c.participation, "amplification": c.amplification,
                           "strength": c.strength, "source": c.source, "order": c.order,
                           "speed_independent": c.speed_independent, "excitation_Hz": c.excitation_Hz}
                          for c in m.crossings],
        } for m in a.modes] for a in analyses},
        "warnings": list(warnings or []),
    }


def modes_csv(analyses: list[ModalAnalysis]) -> str:
    """One row per mode and boundary: the JSON's scalars (frequency, modal damping ratio, dominant element), the
    shape per body, the strain-energy share per element and the crossings as text."""
    first = analyses[0]
    header = (["boundary", "mode", "frequency_Hz", "damping_ratio", "dominant_element"]
              + [f"shape_{b.replace(' ', '_')}" for b in first.bodies]
              + [f"energy_share_{c.replace(' ', '_')}" for c in first.connectors]
              + ["crossings_rpm", "damped_frequency_Hz"])  # the last: added in round 4, earlier columns keep their places
    rows: list[list[JsonScalar]] = []
    for a in analyses:
        for m in a.modes:
            cross = "; ".join(f"{c.excitation} @ {_at(c, '.5g')}" for c in m.crossings)
            rows.append([a.boundary, m.number, m.frequency_Hz, m.damping_ratio, m.dominant,
                         *m.shape, *m.energy_share, cross, m.damped_frequency_Hz])
    return csv_text(header, rows)


def _at(c, fmt: str, units: OutputUnits | None = None) -> str:
    """The crossing's input speed (rpm, or in ``units``), ``any`` for a fixed frequency near the mode at every
    speed."""
    if c.input_speed_rpm is None:
        return "any"
    value = c.input_speed_rpm if units is None else in_speed_unit(c.input_speed_rpm, units)
    return format(value, fmt) if fmt != "table" else figure(value, 4)


def in_speed_unit(rpm: float, units: OutputUnits) -> float:
    """An input speed in rpm in the design file's speed unit."""
    return units.speed_from_deg_s(6.0 * rpm)


def _strength(c) -> str:
    gain = "∞" if c.amplification is None else figure(c.amplification, 2)
    return f"{figure(100 * c.participation, 2)} %, {gain}"


def modes_tables(analyses: list[ModalAnalysis], units: OutputUnits | None = None) -> list[RenderableType]:
    """The modes per boundary, input speeds in the design file's speed unit (``units``; rpm without)."""
    from rich.table import Table  # lazy: rich, imported only for a table
    from rich.text import Text  # lazy: rich, imported only for a table

    u = units or OutputUnits("rpm")
    out: list = []
    for a in analyses:
        also = f" = {a.speed_range_rpm[1]:.5g} rpm" if u.speed == "deg_s" else ""  # °/s files: also rpm
        t = Table(title=f"modes, {a.boundary} (linearised at full load; crossings for input 0 .. "
                        f"{in_speed_unit(a.speed_range_rpm[1], u):.5g} {u.speed_label}{also})", title_justify="left",
                  header_style="bold")
        for col in ("mode", "f [Hz]", "ζ [%]", "rings at [Hz]", "dominant element (share)",
                    f"orders crossing [input {u.speed_label}] (exciting share, resonant gain s/2ζ)"):
            t.add_column(col)
        for m in a.modes:
            share = "rigid-body rotation" if m.rigid else f"{m.dominant} ({100 * max(m.energy_share):.0f} %)"
            cross = ", ".join(f"{c.excitation} @ {_at(c, 'table', u)} ({_strength(c)})" for c in m.crossings) or "-"
            t.add_row(str(m.number), figure(m.frequency_Hz, 4), "-" if m.rigid else figure(100 * m.damping_ratio, 2),
                      "-" if m.damped_frequency_Hz is None else figure(m.damped_frequency_Hz, 4), Text(share),
                      Text(cross))
        out.append(t)
    return out
