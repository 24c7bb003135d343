"""The Campbell diagram (matplotlib Agg), one drawing for ``gearcli modes --plots`` and ``gearcli sweep --plots``.

Input speed from 0 to the top of the range (1.2 x nominal, or the sweep's range), frequency up to the highest
order's frequency there, on a logarithmic axis when the modes and orders span more than two decades (a drum
mode at 5 Hz and a mesh order at 5 kHz both stay readable). Each natural frequency is a horizontal line with its
+-10 % resonance margin band; every order line (mesh 1x-3x, shaft 1x, input torque ripple orders) and every load
fluctuation frequency (a horizontal line) is drawn; every crossing is marked by how
strongly the order excites the mode (its meshes' strain-energy share over twice the modal damping ratio: filled
red strongly, orange moderately, small grey weakly); the nominal speed is a vertical line, and the crossings
inside the margin at the nominal speed are labelled.
"""

from __future__ import annotations

import textwrap
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from gearcli.io.figures import check as _figure_check
from gearcli.io.figures import figure as _figure
from gearcli.io.figures import save as _save
from gearcli.io.figures import suptitle as _suptitle
from gearcli.io.units import OutputUnits
from gearcli.model.campbell import CampbellData
from gearcli.model.modes import RESONANCE_BAND, near_nominal

if TYPE_CHECKING:
    from matplotlib.figure import Figure

TITLE_CHARS = 110  # the axes title's line length at 8.5 pt on the 11 in figure, within the axes' width
STYLES = {"strongly": dict(marker="o", ms=8, mfc="tab:red", mec="darkred", zorder=6),
          "moderately": dict(marker="o", ms=6.5, mfc="orange", mec="darkorange", zorder=5),
          "weakly": dict(marker="o", ms=3.5, mfc="none", mec="0.55", zorder=4)}
ORDER_STYLES = {1: "-", 2: "--", 3: ":"}
MODE_LABEL_PT = 7.5  # the mode labels' font size


def _speed(units: OutputUnits, rpm: Any) -> Any:
    return units.speed_from_deg_s(rpm * 6.0)


def campbell_figure(data: CampbellData, units: OutputUnits, title: str = "",
                    swept: Sequence[float] | None = None) -> Figure:
    """The figure; ``swept``: input speeds (rpm) of a sweep's points, marked on the speed axis, which then spans
    them (from the slowest; a sweep of one speed: from 0)."""
    fig, axes = _figure(1, 1, height=5.6, width=11.0)
    ax = axes[0][0]
    top_speed = _speed(units, data.max_input_rpm)
    low_speed = _speed(units, min(swept)) if swept and min(swept) < max(swept) else 0.0
    low_f = min([m.frequency_Hz for m in data.modes] + [data.top_Hz / 20.0])
    near_top = [m.frequency_Hz for m in data.modes if m.frequency_Hz <= 1.15 * data.top_Hz]
    top_f = 1.1 * max(data.top_Hz, (1 + RESONANCE_BAND) * max(near_top, default=0.0))
    log = top_f / max(low_f, 1e-9) > 100.0
    bottom = low_f / 1.6 if log else 0.0
    shown = [m for m in data.modes if m.frequency_Hz <= top_f]
    # a repeated mode (identical planets) is one line with one label, named by its first mode
    group_of = {n: numbers for numbers, _ in data.repeated for n in numbers}
    dominant = {numbers[0]: label for numbers, label in data.repeated}
    labels: list[tuple[float, str]] = []  # (Hz, text) of each mode line, drawn once the axes are laid out
    for m in shown:
        f = m.frequency_Hz
        group = group_of.get(m.number, (m.number,))
        if m.number != group[0]:
            continue
        ax.axhspan(f * (1 - RESONANCE_BAND), f * (1 + RESONANCE_BAND), color="0.88", zorder=0, lw=0)
        ax.axhline(f, color="k", lw=1.4, zorder=2)
        labels.append((f, f"{_mode_name(group)}: {f:.4g} Hz ({dominant.get(m.number, m.dominant)}, "
                          f"ζ {100 * m.damping_ratio:.2g} %)"))
    n = np.linspace(0.0, data.max_input_rpm, 200)
    stages = sorted({name.split(" mesh")[0] for name, _ in data.orders if name.startswith("stage ")})
    for name, r in data.orders:
        style: Any
        if name.startswith("input torque ripple"):  # an engine order: per input revolution
            colour, style = "tab:brown", (0, (3, 1, 1, 1, 1, 1))
        elif name.startswith("stage "):
            order = int(name.split()[-1].rstrip("x"))
            colour = f"C{stages.index(name.split(' mesh')[0]) % 10}"
            style = ORDER_STYLES.get(order, "-.")
        else:
            colour, style = "0.45", (0, (6, 2, 1, 2))
        line = r * n / 60.0
        keep = line <= top_f * 1.05
        ax.plot(_speed(units, n[keep]), line[keep], ls=style, lw=1.0, color=colour, label=name, zorder=3)
    for name, f in data.fixed:  # a load fluctuation: the same frequency at every speed
        ax.axhline(f, color="tab:olive", lw=1.2, ls=(0, (8, 3)), label=name, zorder=3)
    nominal = _speed(units, data.nominal_input_rpm)
    if low_speed <= nominal <= top_speed:  # (a sweep's range may leave the file's speed out)
        ax.axvline(nominal, color="tab:purple", lw=1.5, ls="--", zorder=4,
                   label=f"nominal speed {nominal:.5g} {units.speed_label}")
    seen: set[str] = set()
    near = []
    for c in data.crossings:
        rpm, f, s = c.crossing.input_speed_rpm, c.frequency_Hz, c.crossing.strength
        if f > top_f:
            continue
        if rpm is None:  # a fixed frequency within the margin of the mode: at every speed, labelled at the left
            ax.annotate(f"{c.crossing.excitation} × mode {c.mode} ({s} excited, any speed)", (0.0, f),
                        xytext=(4, -12), textcoords="offset points", fontsize=7.5, color="darkred", zorder=8)
            continue
        x = _speed(units, rpm)
        label = f"crossing, {s} excited" if s not in seen else None
        seen.add(s)
        ax.plot([x], [f], ls="none", label=label, **STYLES[s])
        if near_nominal(rpm, data.nominal_input_rpm) and s != "weakly":
            near.append(c)
    # coincident orders (a stage's 3rd mesh harmonic on the next stage's 1st: z1 = 3 z3 / i1) cross a mode at one
    # point: one label naming them all, not labels printed over each other
    # (a repeated mode's modes: one point, one label)
    points: dict[tuple[int, float], tuple[Any, list[str]]] = {}  # (mode, speed): its first crossing, the orders
    for c in near:
        first = group_of.get(c.mode, (c.mode,))[0]
        _, names = points.setdefault((first, round(c.crossing.input_speed_rpm or 0.0, 6)), (c, []))
        if c.crossing.excitation not in names:
            names.append(c.crossing.excitation)
    for c, names in points.values():
        x = _speed(units, c.crossing.input_speed_rpm or 0.0)
        right = x > 0.5 * (low_speed + top_speed)  # a label right of a crossing in the right half ran out of the axes on to the
        mode = _mode_name(group_of.get(c.mode, (c.mode,)))
        ax.annotate(f"{', '.join(names)} × {mode}", (x, c.frequency_Hz),  # legend: it ends at the crossing
                    xytext=(-6 if right else 6, -12), textcoords="offset points", ha="right" if right else "left",
                    fontsize=7.5, color="darkred", zorder=8)
    if swept:
        xs = [_speed(units, v) for v in swept]
        ax.plot(xs, [bottom if log else 0.0] * len(xs), "|", color="tab:purple", ms=10, clip_on=False,
                label="swept points")
    ax.set_xlim(low_speed, top_speed)
    if log:
        ax.set_yscale("log")
    ax.set_ylim(bottom, top_f)
    ax.set_xlabel(f"input speed [{units.speed_label}]")
    ax.set_ylabel("frequency [Hz]" + (" (log)" if log else ""))
    ax.grid(alpha=0.3, which="both")
    hidden = len(data.modes) - len(shown)
    note = f"; {hidden} mode{'s' if hidden > 1 else ''} above the highest order not shown" if hidden else ""
    _suptitle(fig, f"Campbell diagram{' — ' + title if title else ''}")
    head = (f"modes {data.boundary.replace('_', ' ')}, linearised at full load; grey bands: ±"
            f"{100 * RESONANCE_BAND:.0f} % resonance margin{note}")
    key = ("markers: crossings, by how strongly the order excites the mode (exciting meshes' strain-energy share / "
           "2ζ; a torque: its body's kinetic-energy share / 2ζ)")
    ax.set_title("\n".join(textwrap.wrap(head, TITLE_CHARS) + textwrap.wrap(key, TITLE_CHARS)), fontsize=8.5,
                 loc="left")
    # the legend beside the axes (a part of the axes' layout), so the figure title and the axes title, above,
    # never run under it as they did with a figure legend in the top right corner
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0, fontsize=7.5)
    _mode_labels(fig, ax, labels, top_speed)
    return fig


def _mode_labels(fig: Figure, ax: Any, labels: list[tuple[float, str]], x: float) -> None:
    """Each mode's label above its line at the right edge. Labels less than a line of text apart (two modes 1 % apart
    on a log axis: a sun-held planetary's planet modes and its in-phase one) share one text, the higher mode's label
    on top, anchored at the highest of their lines, so that none is drawn over another."""
    layout = fig.get_layout_engine()
    if layout is not None:
        layout.execute(fig)  # the axes' final place: where each frequency lands
    line = MODE_LABEL_PT * 1.25 * fig.dpi / 72.0  # a line of the label's text, pixels
    clusters: list[tuple[float, float, list[str]]] = []  # (anchor Hz, its pixel height, texts from the lowest)
    for f, text in sorted(labels):
        y = float(ax.transData.transform((x, f))[1])
        if clusters and y < clusters[-1][1] + (len(clusters[-1][2]) + 0.5) * line:  # inside the text below
            clusters[-1] = (f, y, [*clusters[-1][2], text])
        else:
            clusters.append((f, y, [text]))
    for f, _, texts in clusters:
        ax.annotate("\n".join(reversed(texts)), (x, f), xytext=(-4, 3), textcoords="offset points", ha="right",
                    va="bottom", fontsize=MODE_LABEL_PT, color="k", zorder=7)


def _mode_name(numbers: Sequence[int]) -> str:
    """"mode 4", or a repeated mode's "modes 4-5 (repeated)" (as the resonance warning names it)."""
    return f"modes {numbers[0]}-{numbers[-1]} (repeated)" if len(numbers) > 1 else f"mode {numbers[0]}"


def write_campbell(data: CampbellData, units: OutputUnits, directory: str | Path, title: str = "") -> Path:
    """Write ``campbell.png`` into ``directory`` (created if needed); returns its path."""
    _figure_check()
    out = Path(directory)
    out.mkdir(parents=True, exist_ok=True)
    return _save(campbell_figure(data, units, title), out / "campbell.png")
