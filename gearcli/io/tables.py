"""Rich tables for a person at a terminal. Builders return renderables; ``render`` turns them into text."""

from __future__ import annotations

import io
from typing import Iterable, Sequence

from rich.console import Console, RenderableType
from rich.table import Table
from rich.text import Text

from gearcli.results import DesignResult, SimulationResult


def _g(v: float, digits: int = 5) -> str:
    return f"{v:.{digits}g}"


def _quantity_table(title: str, columns: Sequence[str], rows: Iterable[tuple[str, Sequence[str]]]) -> Table:
    table = Table(title=title, title_justify="left", header_style="bold")
    table.add_column("quantity", style="cyan", no_wrap=True)
    for col in columns:
        table.add_column(col, justify="right")
    for label, cells in rows:
        table.add_row(Text(label), *cells)  # Text: '[mm]' is a unit, not rich markup
    return table


def design_tables(r: DesignResult) -> list[RenderableType]:
    s = r.stages
    cols = [f"stage {st.index}" for st in s]

    def row(label, fn, digits=5):
        return label, [_g(fn(st), digits) for st in s]

    geometry = _quantity_table(f"{r.title or 'design'}: geometry", cols, [
        ("teeth z1 / z2", [f"{st.pinion.teeth} / {st.gear.teeth}" for st in s]),
        row("ratio i", lambda st: st.ratio),
        row("normal module m_n [mm]", lambda st: st.normal_module_mm),
        row("transverse module m_t [mm]", lambda st: st.transverse_module_mm),
        row("helix β [°]", lambda st: st.helix_angle_deg),
        row("base helix β_b [°]", lambda st: st.base_helix_angle_deg),
        row("transverse pressure α_t [°]", lambda st: st.transverse_pressure_angle_deg),
        row("working pressure α_wt [°]", lambda st: st.working_pressure_angle_deg),
        ("hands pinion / gear", [f"{st.pinion.hand} / {st.gear.hand}" for st in s]),
        row("pinion pitch d1 [mm]", lambda st: st.pinion.pitch_diameter_mm),
        row("  gear pitch d2 [mm]", lambda st: st.gear.pitch_diameter_mm),
        row("base d_b1 [mm]", lambda st: st.pinion.base_diameter_mm),
        row("tip d_a1 [mm]", lambda st: st.pinion.tip_diameter_mm),
        row("root d_f1 [mm]", lambda st: st.pinion.root_diameter_mm),
        row("working centre distance a_w [mm]", lambda st: st.center_distance_mm),
        row("tip alteration k", lambda st: st.tip_alteration_coefficient, 4),
        row("contact ratio ε_α", lambda st: st.contact_ratio_transverse, 4),
        row("overlap ratio ε_β", lambda st: st.overlap_ratio, 4),
        row("total ε_γ", lambda st: st.contact_ratio_total, 4),
    ])
    loads = _quantity_table("loads and stiffness", cols, [
        row("pinion speed [rpm]", lambda st: st.pinion.speed_rpm),
        row("pinion torque [N·mm]", lambda st: st.pinion.torque_Nmm),
        row("pinion torque [N·m]", lambda st: st.pinion.torque_Nm),
        row("pinion power [kW]", lambda st: st.pinion.power_kW),
        row("mesh frequency [Hz]", lambda st: st.mesh_frequency_Hz),
        row("F_t tangential [N]", lambda st: st.static_force_N.tangential),
        row("F_r radial [N]", lambda st: st.static_force_N.radial),
        row("F_a axial [N]", lambda st: st.static_force_N.axial),
        row("F_n normal [N]", lambda st: st.static_force_N.normal),
        row("equivalent radius R [mm]", lambda st: st.equivalent_radius_mm),
        row("E* [MPa]", lambda st: st.effective_modulus_MPa, 4),
        row("Hertz K [N/mm^1.5]", lambda st: st.hertz_stiffness_N_mm1_5, 4),
        row("static approach h_0 [mm]", lambda st: st.static_approach_mm, 4),
        row("linearised k [N/mm]", lambda st: st.linearised_stiffness_N_mm, 4),
        row("ISO 6336 c′ [N/(mm·µm)]", lambda st: st.iso6336_single_pair_stiffness_N_mm_um, 4),
        row("ISO 6336 c_γα [N/(mm·µm)]", lambda st: st.iso6336_mesh_stiffness_N_mm_um, 4),
        row("ISO 6336 c_γβ [N/(mm·µm)]", lambda st: st.iso6336_mesh_stiffness_beta_N_mm_um, 4),
        ("ISO 6336 C_M / C_R / C_B", [f"{st.iso6336_factors.C_M:.3g} / {st.iso6336_factors.C_R:.4g} / "
                                      f"{st.iso6336_factors.C_B:.4g}" for st in s]),
        row("ISO 6336 m_red [kg/mm]", lambda st: st.reduced_mass_kg_mm, 4),
        row("ISO 6336 n_E1 [rpm]", lambda st: st.resonance_speed_rpm),
        row("ISO 6336 N = n1/n_E1", lambda st: st.resonance_ratio, 4),
        ("ISO 6336 speed range", [st.resonance_range for st in s]),
    ])
    train = _quantity_table("shafts", [f"shaft {sh.index}" for sh in r.shafts], [
        ("speed [°/s]", [_g(sh.speed_deg_s) for sh in r.shafts]),
        ("speed [rpm]", [_g(sh.speed_rpm) for sh in r.shafts]),
        ("torque [N·mm]", [_g(sh.torque_Nmm) for sh in r.shafts]),
        ("torque [N·m]", [_g(sh.torque_Nm) for sh in r.shafts]),
        ("power [kW]", [_g(sh.power_kW) for sh in r.shafts]),
        ("inertia [kg·m²]", [_g(sh.inertia_kg_m2, 4) for sh in r.shafts]),
    ])
    summary = (f"total ratio {r.total_ratio:.6g}   output {r.output_speed_deg_s:.5g} °/s = "
               f"{r.output_speed_rpm:.4g} rpm   input torque {r.input_torque_Nmm:.5g} N·mm\n"
               f"input torque {r.input_torque_Nmm / 1000:.5g} N·m   input power {r.input_power_kW:.5g} kW")
    return [geometry, loads, train, summary]


def _stats_cells(st) -> list[str]:
    return [_g(st.mean), _g(st.std, 3), _g(st.min), _g(st.max)]


def simulation_tables(r: SimulationResult) -> list[RenderableType]:
    forces = Table(title=f"mesh forces over the steady window {r.window_s[0]:.4g}–{r.window_s[1]:.4g} s",
                   title_justify="left", header_style="bold")
    for name in ("stage", "channel", "mean", "std", "min", "max"):
        forces.add_column(name, justify="left" if name in ("stage", "channel") else "right")
    for s in r.stages:
        forces.add_row(str(s.index), Text("F_t [N]"), *_stats_cells(s.tangential_N))
        forces.add_row("", Text("F_r [N]"), *_stats_cells(s.radial_N))
        forces.add_row("", Text("F_a [N]"), *_stats_cells(s.axial_N))
        forces.add_row("", Text("penetration [mm]"), *_stats_cells(s.penetration_mm), end_section=True)
    peaks = _quantity_table("static theory and peaks", [f"stage {s.index}" for s in r.stages], [
        ("static F_t [N]", [_g(s.static_tangential_N) for s in r.stages]),
        ("peak |F_t| [N]", [_g(s.peak_tangential_N) for s in r.stages]),
        ("at t [s]", [_g(s.peak_time_s, 3) for s in r.stages]),
        ("dynamic factor", [_g(s.dynamic_factor, 4) for s in r.stages]),
    ])
    sv = r.solver
    lines = (f"dynamic ratio {r.ratio:.6g}   output {r.output_speed_deg_s:.6g} °/s\n"
             f"solver {sv.method} ({sv.choice_reason})  rtol {sv.rtol:g}  steps {sv.steps}  nfev {sv.nfev}  "
             f"njev {sv.njev}  wall {sv.wall_s:.3g} s  energy residual {sv.energy_residual:.2e}")
    return [forces, peaks, lines]


def render(renderables: Sequence[RenderableType], *, console: Console | None = None, width: int = 110) -> str | None:
    """Print to ``console`` (a terminal) or, without one, return plain text (for ``-o`` or a pipe)."""
    if console is not None:
        for item in renderables:
            console.print(item)
        return None
    buf = io.StringIO()
    plain = Console(file=buf, width=width, color_system=None, force_terminal=False, highlight=False)
    for item in renderables:
        plain.print(item)
    return buf.getvalue()
