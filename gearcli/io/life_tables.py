"""Tables of shaft statics, bearing lives and the load-to-life calculation (docs/life.md)."""

from __future__ import annotations

from collections.abc import Sequence

from rich.console import RenderableType

from gearcli.io.table_kit import FittedTable, StageColumns, _g, spread
from gearcli.life.result import BearingLife
from gearcli.optional_results import BearingResult
from gearcli.simulate.results import BearingStats


def bearing_table(bearings: Sequence[BearingResult], title: str = "bearings: static reactions and ISO 281 life"
                  ) -> StageColumns:
    """One column per bearing: its place, reaction on the shaft (y, z, radial, axial), P, C, L10, L10h."""
    b = bearings
    return StageColumns(title, [f"bearing {j + 1}" for j in range(len(b))], [
        ("shaft", [f"planets of stage {x.planet_stage}" if x.planet_stage else str(x.shaft) for x in b]),
        ("position x [mm]", [_g(x.position_mm) for x in b]),
        ("kind / locating", [f"{x.kind}{' / loc.' if x.locating else ''}" for x in b]),
        ("speed [rpm]", [_g(x.speed_rpm) for x in b]),
        ("reaction F_y [N]", [_g(x.radial_y_N) for x in b]),
        ("reaction F_z [N]", [_g(x.radial_z_N) for x in b]),
        ("radial F_r [N]", [_g(x.radial_N) for x in b]),
        ("axial F_a [N]", [_g(x.axial_N) for x in b]),
        ("equivalent load P [N]", [_g(x.equivalent_load_N) for x in b]),
        ("rating C [kN]", [_g(x.dynamic_load_rating_kN) for x in b]),
        *life_rows(b),
        *modified_rows(b),
    ])


def unbounded(value: float | None, load_N: float | None, digits: int = 4) -> str:
    """A life or safety cell: ∞ where it is unbounded because the bearing carries no load (ISO 281 L10 = (C/P)^p,
    s_0 = C_0/P_0 with P = 0), as the gear tables print an infinite life; else the number ("—": not computed)."""
    return "∞" if value is None and load_N == 0.0 else _g(value, digits)


def life_rows(b: Sequence[BearingResult] | Sequence[BearingLife]) -> list[tuple[str, list[str]]]:
    """The basic rating life rows L10 and L10h (∞ for an unloaded bearing)."""
    return [("L10 [10^6 rev]", [unbounded(x.L10_Mrev, x.equivalent_load_N) for x in b]),
            ("L10h [h]", [unbounded(x.L10_h, x.equivalent_load_N) for x in b])]


def _given(value: float | None, shown: str) -> str:
    """A cell of a bearing that has the figure's inputs ("—" for one that has not)."""
    return "—" if value is None else shown


def modified_rows(b: Sequence[BearingResult] | Sequence[BearingLife]) -> list[tuple[str, list[str]]]:
    """ISO 281 modified life and ISO 76 static safety rows, only when some bearing has their keys (a bearing
    without them shows —); ``b``: BearingResult or BearingLife."""
    rows: list[tuple[str, list[str]]] = []
    if any(x.fatigue_load_limit_kN is not None for x in b):
        rows += [
            ("viscosity ratio κ", [_given(x.fatigue_load_limit_kN, _g(x.kappa, 4)) for x in b]),
            ("a_ISO (ISO 281)", [_given(x.fatigue_load_limit_kN, _g(x.a_ISO, 4)) for x in b]),
            ("a_1 (reliability)", [_given(x.fatigue_load_limit_kN, _g(x.a_1, 4)) for x in b]),
            ("L_nm [10^6 rev]", [_given(x.fatigue_load_limit_kN, unbounded(x.L_nm_Mrev, x.equivalent_load_N))
                                 for x in b]),
            ("L_nmh [h]", [_given(x.fatigue_load_limit_kN, unbounded(x.L_nm_h, x.equivalent_load_N)) for x in b]),
        ]
    if any(x.static_load_rating_kN is not None for x in b):
        rows += [
            ("static rating C_0 [kN]", [_given(x.static_load_rating_kN, _g(x.static_load_rating_kN)) for x in b]),
            ("static equivalent P_0 [N]", [_given(x.static_load_rating_kN, _g(x.static_equivalent_load_N)) for x in b]),
            ("static safety s_0 = C_0/P_0", [_given(x.static_load_rating_kN,
                                                    unbounded(x.static_safety, x.static_equivalent_load_N))
                                             for x in b]),
        ]
    return rows


def bearing_stats_table(window_s: tuple[float, float], bearings: Sequence[BearingStats]) -> RenderableType:
    """Window statistics of the bearing reaction channels of a simulation (numbers never folded)."""
    names = ("bearing", "shaft", "x [mm]", "channel", "mean", "std", "min", "max")
    rows, ends = [], []
    for j, b in enumerate(bearings):
        for label, st in (("radial [N]", b["radial_N"]), ("axial [N]", b["axial_N"])):
            first = label.startswith("radial")
            place = f"planets {b['planet_stage']}" if b.get("planet_stage") else str(b["shaft"])
            rows.append([str(j + 1) if first else "", place if first else "", _g(b["position_mm"]) if first else "",
                         label, _g(st.mean), spread(st.std, st.mean), _g(st.min), _g(st.max)])
            ends.append(not first and "static_safety_min" not in b)
        if "static_safety_min" in b:  # ISO 76 at the window's peak P_0 (docs/bearings.md)
            rows.append(["", "", "", "static safety s_0 (min)", "", "", _g(b.get("static_safety_min"), 4), ""])
            ends.append(True)
    return FittedTable(f"bearing reactions over the steady window {window_s[0]:.4g}–{window_s[1]:.4g} s", names,
                       rows, [n not in ("bearing", "shaft", "channel") for n in names],
                       justify=["left" if n in ("bearing", "channel") else "right" for n in names], ends=ends)
