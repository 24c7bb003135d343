"""``gearcli life`` output: JSON (docs/life.md, "Output"), CSV (one row per load class) and tables in the
order of an ISO 6336-6 calculation: the duty, the spectrum of each member (class, load, cycles, stress, cycles
to failure, damage), the damage sums, lives and safeties, then the bearings over the duty."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import cast

from rich.console import Console, ConsoleOptions, RenderableType, RenderResult

from gearcli.core.jsontypes import JsonObject, JsonScalar, JsonValue
from gearcli.diagnostics import warning_objects
from gearcli.io.life_tables import life_rows, modified_rows
from gearcli.io.serialize import bearings_csv, csv_text, plain
from gearcli.io.table_kit import FittedTable, StageColumns, _g, text
from gearcli.io.units import OutputUnits
from gearcli.life.result import LifeResult, ModeLife, StageLife, member_label, planet_flank
from gearcli.results import DesignResult, drop_absent_bearing_keys

MEMBERS = ("pinion", "gear")
MODES = ("pitting", "bending")
RING_MEMBERS = ("ring", "planet_ring_side")  # a planetary stage's planet–ring mesh (after pinion, gear)
PLANETARY_ALIASES = ("sun", "planet")  # a planetary stage's members under DESIGN §10's names, beside the per-mesh ones
LABELS = {"pinion": "pinion", "gear": "gear", "ring": "ring", "planet_ring_side": "planet (ring mesh)"}
ROOT_LABEL = "planet root (both meshes)"


def _members(st: StageLife) -> tuple[str, ...]:
    """The stage's members in output order: pinion, gear, and a planetary stage's ring and planet ring side."""
    return (*MEMBERS, *(m for m in RING_MEMBERS if getattr(st, m) is not None))


def _stage_dict(st: StageLife) -> JsonObject:
    out: JsonObject = {"index": st.index, **{m: {mode: _mode_dict(getattr(getattr(st, m), mode)) for mode in MODES}
                                             for m in _members(st)}}
    if st.planet_root is not None:
        out["planet_root"] = {"bending": _mode_dict(st.planet_root)}
    if st.ring is not None and st.planet_ring_side is not None:
        out.update(_planetary_members(st, out))
    return out


def _planetary_members(st: StageLife, out: JsonObject) -> JsonObject:
    """A planetary stage's members under the contract's names (DESIGN §10: ``sun``, ``planet``, ``ring``) beside
    the per-mesh entries: ``sun`` is the sun–planet mesh's ``pinion``; ``planet`` the planet as a whole, its
    flank the more damaged of its two (``gear``, the sun side, and ``planet_ring_side``; ``flank`` says which:
    different flanks, independent damages) and its root ``planet_root`` (both meshes' bending on the same root,
    summed); ``ring`` is already there."""
    assert st.planet_ring_side is not None and st.planet_root is not None
    flank, key = planet_flank(st)  # the sun side on a tie
    pitting = dict(cast(JsonObject, cast(JsonObject, out[key])["pitting"]), flank=flank)
    return {"sun": out["pinion"], "planet": {"pitting": pitting, "bending": cast(JsonObject, out["planet_root"])["bending"]}}


def life_dict(r: LifeResult, design: DesignResult | None = None) -> JsonObject:
    """The life JSON; ``warnings`` are objects (code, message, data), the base file's ``design`` warnings first, as
    stderr says them (docs/output.md, "Warnings")."""
    stages: list[JsonObject] = [_stage_dict(st) for st in r.stages]
    first = warning_objects(design.warnings, design.diagnostics) if design is not None else []
    return {
        "life": {"route": r.route, "miner": r.miner, "standard": r.standard, "hours": r.hours,
                 "stages": stages, "bearings": _bearing_docs(r), "points": plain(r.points)},
        "warnings": first + warning_objects([w for w in r.warnings if design is None or w not in design.warnings],
                                            r.diagnostics),
    }


def life_bearings_csv(r: LifeResult) -> str:
    """``gearcli life --table bearings``: the life JSON's ``bearings``, a row each (per-point lists a column per
    point)."""
    return bearings_csv(_bearing_docs(r))


def _mode_dict(ml: ModeLife) -> JsonObject:
    out: JsonObject = {"damage": ml.damage, "life_h": ml.life_h, "below_endurance": ml.below_endurance,
                       "safety": ml.safety, "load_multiplier": ml.safety, "stress_safety": ml.stress_safety,
                       "curve": ml.curve,
                       "static_cycles": ml.static_cycles, "knee_cycles": ml.knee_cycles,
                       "bins": [{"force_N": b.force_N, "stress_MPa": b.stress_MPa, "cycles": b.cycles,
                                 "cycles_to_failure": b.cycles_to_failure, "damage": b.damage, "point": b.point,
                                 "endurance_MPa": b.endurance_MPa} for b in ml.bins]}
    if ml.planet is not None:  # the dynamic route's planet members: which planet is reported (the worst)
        out["planet"] = ml.planet
    return out


def life_csv(r: LifeResult) -> str:
    header = ["stage", "member", "mode", "point", "force_N", "stress_MPa", "cycles", "cycles_to_failure", "damage",
              "damage_sum", "life_h", "safety", "load_multiplier", "stress_safety", "below_endurance"]
    rows: list[list[JsonScalar]] = []
    for st in r.stages:
        modes: list[tuple[str, str, ModeLife]] = [(m, mode, getattr(getattr(st, m), mode)) for m in _members(st)
                                                  for mode in MODES]
        if st.planet_root is not None:
            modes.append(("planet_root", "bending", st.planet_root))
        for m, mode, ml in modes:
            for b in ml.bins:
                rows.append([st.index, m, mode, b.point, b.force_N, b.stress_MPa, b.cycles,
                             "" if b.cycles_to_failure is None else b.cycles_to_failure, b.damage, ml.damage,
                             "" if ml.life_h is None else ml.life_h, "" if ml.safety is None else ml.safety,
                             "" if ml.safety is None else ml.safety,
                             "" if ml.stress_safety is None else ml.stress_safety, ml.below_endurance])
    return csv_text(header, rows)


def _duty_table(r: LifeResult) -> FittedTable:
    n = len(r.points[0].K_v) if r.points else 0
    u = OutputUnits(*r.units) if r.units is not None else OutputUnits(torque="Nm")  # the file's torque unit
    cols = ["point", "hours", f"output torque [{u.torque_label}]", "input speed [rpm]", "starts",
            *(f"K_v stage {k + 1}" if r.route == "static" else f"max/static F_t st. {k + 1}" for k in range(n))]
    rows = [[p.name, _g(p.hours), _g(u.torque_from_Nm(p.torque_Nm)), _g(p.speed_rpm),
             str(p.start["count"]) if p.start else "0",
             *(_g(k, 4) for k in p.K_v)] for p in r.points]
    return FittedTable(f"duty ({r.route} route): {r.hours:.6g} h in {len(r.points)} point(s)", cols, rows,
                       [c != "point" for c in cols])


def _start_line(name: str, start: JsonObject) -> RenderableType:
    """One point's starts: count, the start's span, its peak F_t per stage and its largest damage share."""
    peaks = cast("Sequence[float]", start["peak_tangential_N"])
    span = cast("Sequence[float]", start["span_s"])
    worst: tuple[float, str] = (0.0, "")
    for k, doc in enumerate(cast("Sequence[dict]", start["damage"])):
        for member, modes in doc.items():
            if member in PLANETARY_ALIASES:  # the contract's names of entries already counted
                continue
            for mode, d in modes.items():
                worst = max(worst, (float(d), f"stage {k + 1} {LABELS.get(member, member)} {mode}"))
    most = f", largest start damage {_g(worst[0], 3)} ({worst[1]})" if worst[1] else ""
    return text(f"point {name}: {start['count']} starts from rest (0–{span[1]:.4g} s each, classes \"{name} "
                f"(start)\" in the spectra), peak F_t {', '.join(_g(x, 5) + ' N' for x in peaks)}{most}")


@dataclass
class _Fitting:
    """A table printed in the first of its ``forms`` (each a list of tables) whose every table keeps all its
    numbers at the width; else the last form. A number is never folded over lines (:class:`FittedTable`)."""

    forms: Sequence[Sequence[FittedTable]]

    def __rich_console__(self, console: Console, options: ConsoleOptions) -> RenderResult:
        def fits(t: FittedTable) -> bool:
            return len(t.columns_for(options.max_width)[0]) == len(t.headers)

        yield from next((f for f in self.forms if all(fits(t) for t in f)), self.forms[-1])


def _spectrum_table(r: LifeResult, stage, member: str) -> _Fitting:
    """ISO 6336-6 style: one row per load class with its cycles, stresses, cycles to failure and damage; on a
    narrower terminal a pitting and a bending table, narrower still the classes, pitting, bending apart."""
    pit, ben = getattr(stage, member).pitting, getattr(stage, member).bending
    which = f", planet {pit.planet} (the most severely loaded)" if pit.planet is not None else ""
    title = f"stage {stage.index} {member_label(stage, member)}{which}: load spectrum and Miner damage"
    point = [[b.point] for b in pit.bins] + [["sum"]]
    load = [[_g(b.force_N, 4), _g(b.cycles, 4)] for b in pit.bins] + [["", _g(sum(b.cycles for b in pit.bins), 4)]]

    def damage(ml: ModeLife) -> list[list[str]]:
        return [[_g(b.stress_MPa, 4), _g(b.cycles_to_failure, 4), _g(b.damage, 3)] for b in ml.bins] + \
            [["", "", _g(ml.damage, 4)]]

    blocks = {"load": (["F_t [N]", "cycles n_i"], load),
              "pitting": (["σ_H [MPa]", "N_i pitting", "n_i/N_i"], damage(pit)),
              "bending": (["σ_F [MPa]", "N_i bending", "n_i/N_i "], damage(ben))}

    def table(name: str, *keys: str) -> FittedTable:
        cols = ["point", *(c for k in keys for c in blocks[k][0])]
        rows = [sum((blocks[k][1][i] for k in keys), point[i]) for i in range(len(point))]
        return FittedTable(name, cols, rows, [c != "point" for c in cols], ends=[False] * (len(rows) - 1) + [True])

    return _Fitting([[table(title, "load", "pitting", "bending")],
                     [table(f"{title} (pitting)", "load", "pitting"), table(f"{title} (bending)", "load", "bending")],
                     [table(title, "load"), table(f"{title} (pitting)", "pitting"),
                      table(f"{title} (bending)", "bending")]])


SYMBOL = {"pitting": "S_H", "bending": "S_F"}


def _life_cell(ml: ModeLife | None) -> str:
    """The life in hours; ∞ where no class exceeds the endurance limit (or nothing damages)."""
    if ml is None:
        return "—"
    return "∞" if ml.life_h is None and (ml.below_endurance or ml.damage == 0.0) else _g(ml.life_h, 4)


def _summary(r: LifeResult) -> StageColumns:
    """Per member: damage, life and, labelled apart, the load multiplier to D = 1 (on the tooth force) and the
    stress safety it means (on σ_H: its square root; on σ_F: itself), the one to compare with S_H, S_F."""
    cols: list[str] = []
    labels = {}
    for mode in MODES:
        labels[mode] = (f"D {mode}", f"life {mode} [h]", f"load multiplier {mode} (on F)",
                        f"stress safety {SYMBOL[mode]} {mode} (on σ)")
    rows: dict[str, list[str]] = {label: [] for mode in MODES for label in labels[mode]}

    def add(mode: str, ml: ModeLife | None) -> None:
        d, life, load, stress = labels[mode]
        rows[d].append("—" if ml is None else _g(ml.damage, 4))
        rows[life].append(_life_cell(ml))
        rows[load].append("—" if ml is None else _g(ml.safety, 4))
        rows[stress].append("—" if ml is None else _g(ml.stress_safety, 4))

    for st in r.stages:
        for m in _members(st):
            cols.append(f"stage {st.index} {member_label(st, m)}")
            for mode in MODES:
                add(mode, getattr(getattr(st, m), mode))
        if st.planet_root is not None:
            cols.append(f"stage {st.index} {ROOT_LABEL}")
            for mode in MODES:
                add(mode, st.planet_root if mode == "bending" else None)
    return StageColumns("Miner damage over the duty, life and spectrum safety", cols, list(rows.items()))


def _bearing_docs(r: LifeResult) -> JsonValue:
    """The bearings' JSON: ``planet_stage`` only on a planet pin's bearings (a shaft's keep their keys)."""
    docs = []
    for b in r.bearings:
        doc = plain(b)
        assert isinstance(doc, dict)
        if not b.planet_stage:
            doc.pop("planet_stage")
        docs.append(drop_absent_bearing_keys(doc))
    return docs


def _bearings(r: LifeResult) -> StageColumns:
    b = r.bearings
    return StageColumns("bearings over the duty, ISO 281", [f"bearing {j + 1}" for j in range(len(b))], [
        ("shaft", [f"planets of stage {x.planet_stage}" if x.planet_stage else str(x.shaft) for x in b]),
        ("position x [mm]", [_g(x.position_mm) for x in b]),
        ("kind", [x.kind for x in b]),
        *[(f"P at {p.name} [N]", [_g(x.loads_N[i]) for x in b]) for i, p in enumerate(r.points)],
        ("equivalent load P [N]", [_g(x.equivalent_load_N) for x in b]),
        ("rating C [kN]", [_g(x.dynamic_load_rating_kN) for x in b]),
        ("revolutions over the duty", [_g(x.revolutions, 4) for x in b]),
        *life_rows(b),
        *modified_rows(b),
    ])


def life_tables(r: LifeResult) -> list[RenderableType]:
    out: list[RenderableType] = [_duty_table(r)]
    out += [_spectrum_table(r, st, m) for st in r.stages for m in _members(st)]
    out.append(_summary(r))
    if r.bearings:
        out.append(_bearings(r))
    out.append(text(f"S–N curves: {r.miner}; stresses: {r.standard}, K_A = 1 (the spectrum is the load)"
                    + ("" if r.route == "static" else ", K_v = 1 (the simulated mesh-cycle peaks replace it)")))
    for p in r.points:
        if p.start:
            out.append(_start_line(p.name, p.start))
    for p in r.points:
        if p.solver:
            s = p.solver
            window = cast("Sequence[float]", s["window_s"])
            runs = s.get("runs") or 1
            whole = f" (its {runs} runs: nfev {s['total_nfev']}, wall {s['total_wall_s']:.3g} s)" \
                if isinstance(runs, int) and runs > 1 else ""
            out.append(text(f"point {p.name}: {s['method']} ({s['engine']}) rtol {s['rtol']:g}, nfev {s['nfev']}, "
                            f"wall {s['wall_s']:.3g} s{whole}, window {window[0]:.4g}–{window[1]:.4g} s, "
                            f"mesh cycles {', '.join(str(c) for c in p.mesh_cycles)}, peak error "
                            f"{', '.join(f'{e:.1e}' for e in p.peak_error)}, statistics "
                            f"{'resolved' if s['statistics_resolved'] else 'NOT resolved'}"))
    return out
