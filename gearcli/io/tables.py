"""Rich tables for a person at a terminal. Builders return renderables; ``render`` turns them into text.

A table never cuts a number (docs/output.md, "Tables"): a table with a column per stage is split into
several tables of as many stage columns as the width holds (stages 1–4, 5–8 ...), and every table is a
:class:`FittedTable`, whose number columns are as wide as their numbers (labels and headers fold), and which
leaves out its rightmost number columns, with a note, when even that does not fit. Titles and labels are ``Text``: literal,
never rich markup, control characters escaped.
"""

from __future__ import annotations

import io
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Protocol, cast

from rich.console import Console, RenderableType

from gearcli.core.records import record
from gearcli.io.life_out import life_tables as _life_tables
from gearcli.io.life_tables import bearing_stats_table, bearing_table
from gearcli.io.table_kit import (
    FittedTable,
    StageColumns,
    _g,
    _quantity_table,
    limits,
    output_width,
    spread,
    text,
)
from gearcli.io.units import input_torque_window_means, of_result
from gearcli.rating import for_rating
from gearcli.results import DesignResult, RatedMesh, StageResult
from gearcli.simulate.results import SamplingError, SimulationResult, StageDynamics
from gearcli.stages import kinds
from gearcli.stages.design import gear_pairs

if TYPE_CHECKING:
    from gearcli.life.result import LifeResult



def design_tables(r: DesignResult) -> list[RenderableType]:
    """The design's tables: the gear stages' geometry, loads and rating (a column per stage whose kind is a gear
    pair), each kind's own tables, the shafts, the bearings and the summary lines."""
    s = [st for _, st in gear_pairs(r.stages)]
    cols = [f"stage {st.index}" for st in s]
    speeds, torques = _speed_units(r), _torque_units(r)

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
        row("pinion base d_b1 [mm]", lambda st: st.pinion.base_diameter_mm),
        row("  gear base d_b2 [mm]", lambda st: st.gear.base_diameter_mm),
        row("pinion tip d_a1 [mm]", lambda st: st.pinion.tip_diameter_mm),
        row("  gear tip d_a2 [mm]", lambda st: st.gear.tip_diameter_mm),
        row("pinion root d_f1 [mm]", lambda st: st.pinion.root_diameter_mm),
        row("  gear root d_f2 [mm]", lambda st: st.gear.root_diameter_mm),
        row("working centre distance a_w [mm]", lambda st: st.center_distance_mm),
        row("tip alteration k", lambda st: st.tip_alteration_coefficient, 4),
        row("contact ratio ε_α", lambda st: st.contact_ratio_transverse, 4),
        row("overlap ratio ε_β", lambda st: st.overlap_ratio, 4),
        row("total ε_γ", lambda st: st.contact_ratio_total, 4),
    ])
    def pinion(label, fn):  # a kind whose members are not a pinion's has its own table (a planetary's sun, …)
        return label, [_g(fn(st)) if _kind(st).pair_members else "—" for st in s]

    parallel = any(_kind(st).pair_members for st in s)
    loads = _quantity_table("loads and stiffness", cols, [
        *([*(pinion(f"pinion speed [{unit}]", lambda st, f=f: f(st.pinion.speed_deg_s)) for unit, f in speeds),
           *(pinion(f"pinion torque [{unit}]", lambda st, f=f: f(st.pinion.torque_Nmm)) for unit, f in torques),
           pinion("pinion power [kW]", lambda st: st.pinion.power_kW)] if parallel else []),
        row("mesh frequency [Hz]", lambda st: st.mesh_frequency_Hz),
        row("F_t tangential [N]", lambda st: st.static_force_N.tangential),
        row("F_r radial [N]", lambda st: st.static_force_N.radial),
        row("F_a axial [N]", lambda st: st.static_force_N.axial),
        row("F_n normal [N]", lambda st: st.static_force_N.normal),
        row("equivalent radius R [mm]", lambda st: st.equivalent_radius_mm),
        row("E* [MPa]", lambda st: st.effective_modulus_MPa, 4),
        row("Hertz K [N/mm^1.5]", lambda st: st.hertz_stiffness_N_mm1_5, 4),
        *_law_rows(s),
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
        *((f"speed [{unit}]", [_g(f(sh.speed_deg_s)) for sh in r.shafts]) for unit, f in speeds),
        *((f"torque [{unit}]", [_g(f(sh.torque_Nmm)) for sh in r.shafts]) for unit, f in torques),
        ("power [kW]", [_g(sh.power_kW) for sh in r.shafts]),
        ("inertia [kg·m²]", [_g(sh.inertia_kg_m2, 4) for sh in r.shafts]),
    ])
    output = " = ".join(f"{f(r.output_speed_deg_s):{'.4g' if j else '.5g'}} {unit}" for j, (unit, f) in enumerate(speeds))
    torque = " = ".join(f"{f(r.input_torque_Nmm):.5g} {unit}" for unit, f in torques)
    summary = [text(f"total ratio {r.total_ratio:.6g}   output {output}"),
               text(f"input torque {torque}   input power {r.input_power_kW:.5g} kW")]
    rated = [st for st in s if st.rating is not None]
    gears = [geometry, loads] if s else []  # a train without gear stages (all belts) has no gear columns
    own = [*_allowance_table(s), *_kind_tables(r)]
    if r.bearings:  # [[bearing]] tables: shaft statics and ISO 281 (docs/life.md)
        return [*gears, *([rating_table(rated)] if rated else []), *own, train, bearing_table(r.bearings), *summary]
    return [*gears, *([rating_table(rated)] if rated else []), *own, train, *summary]


def _speed_units(r: DesignResult) -> list[tuple[str, Callable[[float], float]]]:
    """The design file's speed unit for the table (DESIGN §12), from °/s: a °/s or rad/s file also in rpm, as the
    simulate and report footers give them."""
    return of_result(r).table_speeds()


def _torque_units(r: DesignResult) -> list[tuple[str, Callable[[float], float]]]:
    """The design file's torque unit for the table (DESIGN §12: torque_Nm → N·m everywhere), from N·mm: an N·mm
    file also in N·m."""
    return of_result(r).table_torques()


def _law_rows(stages: Sequence[StageResult]) -> list[tuple[str, list[str]]]:
    """The mesh law each stage runs (DESIGN section 13's ``mesh_stiffness``: a planetary's sun–planet mesh), its K,
    its tangent where the models linearise it and ISO's k_n beside it: the static approach and linearised stiffness
    below are this law's, not the Hertz K's above (unless the law is "hertz")."""
    laws = [st.mesh_stiffness for st in stages]

    def cells(fn) -> list[str]:
        return ["—" if law is None else fn(law) for law in laws]

    return [("mesh law", cells(lambda law: f"{law.law}, e = {law.exponent:g}")),
            ("law K [N/mm^e]", cells(lambda law: _g(law.K, 4))),
            ("law tangent, models [N/mm]", cells(lambda law: _g(law.linearised_N_mm, 4))),
            ("ISO k_n = c_γα b / cos² β_b [N/mm]", cells(lambda law: _g(law.iso_N_mm, 4)))]


class StageOutput(Protocol):
    """What the tables ask of a stage's kind (its output facet, :mod:`gearcli.stages.io`, registered when
    ``gearcli.io`` is imported)."""

    @property
    def pair_members(self) -> bool:
        """The stage's members are a pinion and a gear (their rows in the loads table)."""

    @property
    def pair_names(self) -> tuple[str, str] | None:
        """The names of its pair's members where they are not a pinion and a gear (a planetary's sun, planet)."""

    @property
    def load_sharing(self) -> bool:
        """The stage's rating has a load-sharing factor K_γ (a row of the rating table)."""

    def design_tables(self, r: DesignResult, stages: list[StageResult]) -> list[RenderableType]:
        """The kind's own tables of ``stages`` (the design's stages of this kind), after the allowances."""

    def simulation_tables(self, r: SimulationResult, stages: list[StageDynamics]) -> list[RenderableType]:
        """The kind's own tables of a run's ``stages`` (its stages' statistics), after the planets' tables."""


def _kind(st: object) -> StageOutput:
    """The output facet of a stage's kind."""
    return cast(StageOutput, kinds.facet(kinds.kind_of(st), "io"))


def _kind_simulation_tables(r: SimulationResult) -> list[RenderableType]:
    """Each stage kind's own tables of the run (a belt's span force and stretch), kinds in stage order."""
    order = list(dict.fromkeys(kinds.kind_of(st) for st in r.stages))
    return [t for name in order
            for t in _kind(r.stages[[kinds.kind_of(st) for st in r.stages].index(name)]).simulation_tables(
                r, [st for st in r.stages if kinds.kind_of(st) == name])]


def _kind_tables(r: DesignResult) -> list[RenderableType]:
    """Each stage kind's own tables (a planetary's members and planet–ring mesh), kinds in stage order."""
    order = list(dict.fromkeys(kinds.kind_of(st) for st in r.stages))
    return [t for name in order
            for t in _kind(r.stages[[kinds.kind_of(st) for st in r.stages].index(name)]).design_tables(
                r, [st for st in r.stages if kinds.kind_of(st) == name])]


def _allowance_table(stages: list) -> list[RenderableType]:
    """Tooth-thickness allowances (ISO 21771): only gear stages that give allowance keys have figures."""
    s = [st for st in stages if st.backlash_circumferential_mm is not None]
    if not s:
        return []
    # a kind whose pair members have names of their own (a planetary's sun–planet mesh: its pinion is the sun, its
    # gear a planet) names them
    named = [n for st in s if (n := _kind(st).pair_names)]
    one, two = (f"pinion/{named[0][0]}", f"gear/{named[0][1]}") if named else ("pinion", "  gear")
    heads = [f"stage {st.index}" + (f" {n[0]}–{n[1]}" if (n := _kind(st).pair_names) else "") for st in s]
    return [_quantity_table("allowances (ISO 21771): [upper / lower] limits", heads, [
        (f"{one} x_E e / i", [limits(st.pinion.generating_profile_shift, 4) for st in s]),
        (f"{two} x_E e / i", [limits(st.gear.generating_profile_shift, 4) for st in s]),
        (f"{one} d_f e / i [mm]", [limits(st.pinion.manufactured_root_diameter_mm, 3) for st in s]),
        (f"{two} d_f e / i [mm]", [limits(st.gear.manufactured_root_diameter_mm, 3) for st in s]),
        ("backlash j_t max / min [mm]", [limits(st.backlash_circumferential_mm, 3) for st in s]),
        ("backlash j_n max / min [mm]", [limits(st.backlash_normal_mm, 3) for st in s]),
        ("ε_α e / m / i", [limits(st.contact_ratio_transverse_with_allowances, 3) for st in s]),
    ])]


class _HasRating(Protocol):
    """What ``rating_table`` reads of a stage (a design's, a simulation's) or a mesh: its index and rating."""

    @property
    def index(self) -> int: ...

    @property
    def rating(self) -> RatedMesh | None: ...


def _rating(st: _HasRating) -> RatedMesh:
    if st.rating is None:
        raise ValueError(f"stage {st.index} has no rating")
    return st.rating


def rating_table(stages: Sequence[_HasRating], title: str = "strength rating, {standard}") -> StageColumns:
    """The rated meshes' rows as their standard gives them (:meth:`gearcli.rating.RatingStandard.table_rows`), one
    column per stage (every mesh rated by one standard: the design file's); ``{standard}`` in ``title`` is its
    title."""
    cols = [f"stage {st.index}" for st in stages]
    ratings = [_rating(st) for st in stages]
    shared = any(getattr(r, "K_gamma", 1.0) != 1.0 or _kind(st).load_sharing
                 for r, st in zip(ratings, stages, strict=True))
    return _quantity_table(title.format(standard=ratings[0].standard), cols, for_rating(ratings[0]).table_rows(ratings, shared=shared))


def _stats_cells(st) -> list[str]:
    return [_g(st.mean), spread(st.std, st.mean), _g(st.min), _g(st.max)]


def simulation_tables(r: SimulationResult) -> list[RenderableType]:
    """The run's tables: the gear stages' mesh forces, peaks and mesh response, stiffness and error estimate (a
    column per stage whose kind is a gear pair), the bearings, the planets, each kind's own tables, the
    simulated rating and the footer lines."""
    gear = [s for _, s in gear_pairs(r.stages)]
    force_rows: list[tuple[str, ...]] = []
    ends: list[bool] = []
    for s in gear:
        force_rows += [(str(s.index), "F_t [N]", *_stats_cells(s.tangential_N)), ("", "F_r [N]", *_stats_cells(s.radial_N)),
                 ("", "F_a [N]", *_stats_cells(s.axial_N)),
                 ("", "penetration [mm]", *_stats_cells(s.penetration_mm))]
        ends += [False, False, False, True]
    forces = FittedTable(f"mesh forces over the steady window {r.window_s[0]:.4g}–{r.window_s[1]:.4g} s",
                         ("stage", "channel", "mean", "std", "min", "max"), force_rows,
                         (False, False, True, True, True, True), ends=ends)
    peaks = _quantity_table("static theory, peaks and mesh response", [f"stage {s.index}" for s in gear], [
        ("static F_t [N]", [_g(s.static_tangential_N) for s in gear]),
        *([("static F_t as simulated [N]", [_g(s.simulated_static_tangential_N) for s in gear])]
          if any(s.simulated_static_tangential_N is not None
                 and abs(s.simulated_static_tangential_N - s.static_tangential_N)
                 > 1e-9 * abs(s.static_tangential_N) for s in gear) else []),
        ("peak |F_t| [N]", [_g(s.peak_tangential_N) for s in gear]),
        ("at t [s]", [_g(s.peak_time_s, 3) for s in gear]),
        ("dynamic factor (window max / static)", [_g(s.dynamic_factor, 4) for s in gear]),
        ("run-up factor (run peak / static)", [_g(s.runup_factor, 4) for s in gear]),
        ("DTE mean [µm]", [_g(s.dte_um.mean) if s.dte_um else "—" for s in gear]),
        ("DTE rms about mean [µm]", [spread(s.dte_um.rms, s.dte_um.mean) if s.dte_um else "—" for s in gear]),
        ("DTE min / max [µm]", [f"{_g(s.dte_um.min)} / {_g(s.dte_um.max)}" if s.dte_um else "—" for s in gear]),
        ("contact loss fraction", [_g(s.contact_loss_fraction, 3) for s in gear]),
        ("back flank fraction", [_g(s.back_flank_fraction, 3) for s in gear]),
        ("regime", [s.regime or "—" for s in gear]),
    ])
    rows = [("mesh stiffness K [N/mm^e]", [_g(m.law_N_mm_e) if (m := s.mesh_stiffness) else "—" for s in gear]),
            ("exponent e", [_g(m.exponent, 3) if (m := s.mesh_stiffness) else "—" for s in gear]),
            ("linearised at static load [N/mm]",
             [_g(m.linearised_N_mm) if (m := s.mesh_stiffness) else "—" for s in gear])]
    rows += [(f"est. error {q} F_t [N]", [_g(_est(s.error_estimate, q), 2) for s in gear])
             for q in ("min", "max", "std")]
    rows.append(("sampling error min / max F_t [N]", [_sampling_cell(s.sampling_error) for s in gear]))
    rows.append(("statistics resolved (mean 1e-4, else 1e-3)", [_resolved(s) for s in gear]))
    mesh = _quantity_table("mesh stiffness used and error estimate", [f"stage {s.index}" for s in gear], rows)
    sv = r.solver
    lines = [footer_speeds(r)]
    means = input_torque_window_means(r)
    if means is not None:
        u = of_result(r)
        both = f" = {means[0]:.5g} N·m" if u.torque == "Nmm" else ""
        lines.append(f"input torque {u.torque_from_Nm(means[0]):.5g} {u.torque_label}{both}, power {means[1]:.5g} kW "
                     f"(means over the steady window {r.window_s[0]:.4g}–{r.window_s[1]:.4g} s)")
    motor = (r.extra or {}).get("motor")
    slip = motor.get("operating_slip") if motor else None
    if motor and slip is not None:
        start = "not reached" if motor["start_time_s"] is None else f"{motor['start_time_s']:.4g} s"
        point = "none" if motor["operating_point_rpm"] is None else f"{motor['operating_point_rpm']:.5g} rpm"
        lines.append(f"motor: start to 98 % {start}   window mean {motor['operating_speed_rpm']:.5g} rpm, slip "
                     f"{100 * slip:.3g} %   operating point of the curves {point}")
    lines.append(f"solver {sv.method}  rtol {sv.rtol:g}  steps {sv.steps}  nfev {sv.nfev}  njev {sv.njev}  "
                 f"wall {sv.wall_s:.3g} s" + (f"   (the result's {sv.runs} runs: nfev {sv.total_nfev}, wall "
                                              f"{sv.total_wall_s:.3g} s)" if sv.runs > 1 else ""))
    lines.append(f"energy residual {sv.energy_residual:.2e}")
    lines.append(f"method: {sv.choice_reason}")
    steady = steady_line(r)
    if steady:
        lines.append(steady)
    if sv.check_pass:
        cp = sv.check_pass
        lines.append(f"error estimate: check pass at rtol {cp['rtol']:g} from {cp['from_s']:.4g} s, nfev {cp['nfev']}, "
                     f"wall {cp['wall_s']:.3g} s")
    # one Text per line: text() writes a control character (a newline too) as an escape
    rated = [st for st in r.stages if st.rating is not None]
    simulated = [rating_table(rated, "strength rating at the simulated K_v, {standard}")] if rated else []
    rings = [_RingRating(st.index, st.planet_ring_rating) for st in r.stages if st.planet_ring_rating is not None]
    if rings:
        simulated.append(rating_table(rings, "planet–ring mesh strength rating at the simulated K_v, {standard} "
                                             "(p planet, g ring)"))
    own = [*_planet_tables(r), *_kind_simulation_tables(r)]
    head: list[RenderableType] = [forces] if gear else []  # a run without gear stages (all belts): no mesh tables
    tail: list[RenderableType] = [peaks, mesh] if gear else []
    if r.extra and r.extra.get("bearings"):  # [[bearing]] tables (docs/life.md)
        return [*head, bearing_stats_table(r.window_s, r.extra["bearings"]), *tail, *own, *simulated,
                *(text(line) for line in lines)]
    return [*head, *tail, *own, *simulated, *(text(line) for line in lines)]


def _sampling_cell(e: SamplingError | None) -> str:
    """The sampling estimate's min / max, or what the samples cannot bound (docs/numerics.md, "Aliasing")."""
    if e is None:
        return "—"
    if e.aliased:
        return f"not bounded ({_g(cast(float, e.aliased.get('frequency_Hz')), 4)} Hz aliased)"
    return f"{_g(e.min_N, 2)} / {_g(e.max_N, 2)}"


@record
class _RingRating:
    """A planetary stage's planet–ring rating as a stage with a rating (rating_table's rows)."""

    index: int
    rating: RatedMesh


def _planet_tables(r: SimulationResult) -> list[RenderableType]:
    """A planetary stage: every planet's sun- and ring-mesh F_t and DTE over the window, the sharing factor."""
    out: list[RenderableType] = []
    for s in r.stages:
        if not s.planets:
            continue
        rows: list[tuple[str, ...]] = []
        ends: list[bool] = []
        for p in s.planets:
            for label, m in (("sun", p.sun), ("ring", p.ring)):
                rows.append((str(p.index) if label == "sun" else "", label, _g(m.tangential_N.mean),
                             spread(m.tangential_N.std, m.tangential_N.mean), _g(m.dte_um.mean),
                             spread(m.dte_um.rms, m.dte_um.mean)))
                ends.append(label == "ring")
        # a fitted table: a narrow terminal leaves columns out rather than splitting a number
        out.append(FittedTable(f"stage {s.index}: planets over the steady window (load-sharing factor "
                               f"{_g(s.load_sharing_factor, 5)})",
                               ("planet", "mesh", "F_t mean [N]", "F_t std [N]", "DTE mean [µm]", "DTE rms [µm]"),
                               rows, (False, False, True, True, True, True), ends=ends))
    return out


def footer_speeds(r: SimulationResult) -> str:
    """The dynamic ratio and the window-mean speeds in the design file's speed unit (°/s and rad/s: also rpm)."""
    u = of_result(r)
    return (f"dynamic ratio {r.ratio:.6g}   output {u.speed_text(r.output_speed_deg_s)}   "
            f"input {u.speed_text(r.input_speed_deg_s)}")


def _resolved(s: StageDynamics) -> str:
    """The stage's verdict: the solver's and the sampling's estimates together; the samples' alone without a
    check pass ("—" when neither ran)."""
    if s.error_estimate is not None:
        return "yes" if s.error_estimate.resolved else "NO"
    if s.sampling_error is not None and not s.sampling_error.resolved:
        return "NO (samples)"
    return "—" if s.sampling_error is None else "samples only: yes"


def _est(e, q: str) -> float | None:
    return None if e is None else getattr(e.tangential_N, q)


def steady_line(r: SimulationResult) -> str:
    """The ``[simulation] steady`` outcome in one line (empty for a window run without excitation data)."""
    st = r.steady
    if st is None or st.mode != "periodic":
        return ""
    found = f"{st.periodicity}, converged" if st.converged else "none found (not periodic), not converged"
    residual = f"{st.residual:.2g}" if st.residual is not None else "—"
    how = "" if st.method is None else f", found by {st.method}" + (
        f" ({st.iterations} Newton steps)" if st.method == "shooting" else "")
    floq = "" if st.spectral_radius is None else (f", Floquet |mu|max {st.spectral_radius:.4g}"
                                                  + ("" if st.bifurcation in (None, "none") else f" ({st.bifurcation} near)"))
    return (f"steady periodic: period {_g(st.period_s or 0.0)} s{how}, {st.periods_to_converge} periods integrated "
            f"(cap {st.cap_periods}), {found}, residual {residual} x tolerance, statistics over "
            f"{st.window_periods} period(s){floq}")


class _Buffer(io.StringIO):
    """A text buffer that tells rich the encoding of where the text goes (ASCII boxes when not UTF)."""

    def __init__(self, encoding: str) -> None:
        super().__init__()
        self._encoding = encoding

    @property
    def encoding(self) -> str:  # type: ignore[override]
        return self._encoding


def render(renderables: Sequence[RenderableType], *, console: Console | None = None,
           width: int | None = None, encoding: str = "utf-8") -> str | None:
    """Print to ``console`` (a terminal) or, without one, return plain text (for ``-o`` or a pipe) at
    ``width`` (default :func:`output_width`), with ASCII boxes when ``encoding`` is not a UTF."""
    if console is not None:
        for item in renderables:
            console.print(item)
        return None
    buf = _Buffer(encoding)
    plain = Console(file=buf, width=width or output_width(), color_system=None, force_terminal=False,
                    highlight=False, markup=False, emoji=False)
    for item in renderables:
        plain.print(item)
    return buf.getvalue()


def life_tables(r: LifeResult) -> list[RenderableType]:
    """``gearcli life`` tables (gearcli.io.life_out)."""
    return _life_tables(r)
