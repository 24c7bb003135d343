"""``gearcli sweep --plots DIR``: response curves, a Campbell diagram, histograms and ECDFs (matplotlib Agg).

- ``response_<key>.png`` for each ``--vary`` key: every statistic with data against the key, one column per
  stage, each direction (up, down, or independent points) in its own colour and overlaid; in a grid each
  combination of the other varied keys' values in its own colour, the direction by its marker (up ^, down v).
- ``campbell.png`` when the input speed is swept: the Campbell diagram of ``gearcli modes --plots``
  (:mod:`gearcli.io.campbell`) over the swept range, the swept speeds marked.
- ``distributions.png`` for ``--random`` samples: histogram and empirical CDF of the main statistics, one
  distribution per point of a ``--vary`` grid.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from gearcli.errors import GearcliError
from gearcli.io import campbell as campbell_io
from gearcli.io.figures import figure as _figure
from gearcli.io.figures import save as _save
from gearcli.io.figures import suptitle as _suptitle
from gearcli.io.units import OutputUnits
from gearcli.sweep.columns import Row
from gearcli.sweep.modes import SweepCampbell
from gearcli.sweep.session import Session
from gearcli.sweep.spec import canonical_key

COLOURS = {"up": "tab:blue", "down": "tab:red", "none": "tab:green"}
MARKERS = {"up": "^", "down": "v", "none": "."}
#: (title with unit, columns of one stage as {suffix: line style})
FAMILIES = (
    ("tangential force F_t (N)", {"tangential_N_mean": "-", "tangential_N_min": ":", "tangential_N_max": "--"}),
    ("F_t standard deviation (N)", {"tangential_N_std": "-"}),
    ("dynamic transmission error (µm)", {"dte_um_mean": "-", "dte_um_min": ":", "dte_um_max": "--"}),
    ("DTE rms (µm)", {"dte_um_rms": "-"}),
    ("contact loss (fraction of window)", {"contact_loss_fraction": "-"}),
    ("dynamic factor: window max / static F_t (-)", {"dynamic_factor": "-"}),
    ("run-up factor: run peak / static F_t (-)", {"runup_factor": "-"}),
)
#: the column whose magnitude a family's values are measured against (a std is zero at the scale of its mean)
SCALE_OF = {"tangential_N_std": "tangential_N_mean", "dte_um_rms": "dte_um_mean"}
#: families that cannot be negative, whose pinned axis starts at zero
NON_NEGATIVE = ("tangential_N_std", "dte_um_rms", "contact_loss_fraction")
#: legend entries (curves x line styles) that fit inside the first panel; more go below the panels
LEGEND_INSIDE = 6
#: relative spread below which a family's values differ by roundoff only (an equilibrium row's std is ~1e-13 N)
ROUNDOFF = 1e-9
DISTRIBUTION_STATS = (("tangential_N_max", "peak F_t in window (N)"), ("tangential_N_std", "F_t std (N)"),
                      ("dynamic_factor", "dynamic factor (-)"), ("dte_um_rms", "DTE rms (µm)"))


def _num(v: Any) -> float:
    try:
        return float(v)
    except (TypeError, ValueError):
        return float("nan")


def _has(rows: Sequence[dict], col: str) -> bool:
    return any(np.isfinite(_num(r.get(col))) for r in rows)


def write_sweep_plots(session: Session, rows: Sequence[Row], plots_dir: str,
                      campbell: SweepCampbell | None = None) -> list[Path]:
    """The sweep's figures into ``plots_dir``; ``campbell`` (:func:`gearcli.api.sweep_campbell`, computed by the
    caller when an input speed is swept) gives ``campbell.png``."""
    out = Path(plots_dir)
    ok = [r for r in rows if r.get("status") == "ok"]
    failed = [r for r in rows if r.get("status") == "failed"]
    n_stages = session.scene.n_stages
    paths: list[Path] = []
    figs = []
    for axis in session.spec.axes:
        figs.append((response_name(axis.key), _response(ok, axis.column, session.spec, n_stages, failed)))
    if campbell is not None:
        figs.append(("campbell.png", _campbell(campbell)))
    if session.spec.randoms:
        grid = [a.column for a in session.spec.axes]
        figs.append(("distributions.png", _distributions(ok, n_stages, grid, len(failed))))
    figs = [(name, fig) for name, fig in figs if fig is not None]
    if figs:  # a sweep whose every point failed has nothing to draw: no empty directory either
        out.mkdir(parents=True, exist_ok=True)
    for name, fig in figs:
        paths.append(_save(fig, out / name))
    return paths


def response_name(key: str) -> str:
    """The response figure's file of a varied key in either spelling: ``stage[0].backlash_mm`` and
    ``stage.0.backlash_mm`` are ``response_stage_0_backlash_mm.png`` (``--plots``' check before the sweep named
    the first ``response_stage[0]_backlash_mm.png``, not the file written)."""
    try:
        key = canonical_key(key)
    except GearcliError:  # a malformed key: --vary's own check names it
        pass
    return f"response_{key.replace('.', '_')}.png"


def _groups(rows: Sequence[dict], key: str, keys: Sequence[str]) -> dict[tuple, list[dict]]:
    """Rows per direction and combination of the other varied keys, each sorted by ``key``."""
    others = [k for k in keys if k != key]
    groups: dict[tuple, list[dict]] = {}
    for r in rows:
        groups.setdefault((r.get("direction"), *(str(r.get(k)) for k in others)), []).append(r)
    return {g: sorted(rs, key=lambda r: _num(r.get(key))) for g, rs in groups.items()}


def _response(rows: Sequence[dict], key: str, spec, n_stages: int, failed: Sequence[dict] = ()):
    families = [(t, cols) for t, cols in FAMILIES
                if any(_has(rows, f"stage{k}_{c}") for k in range(1, n_stages + 1) for c in cols)]
    if not rows or not families:
        return None
    fig, axes = _figure(len(families) + 1, n_stages, height=2.1, width=4.2 * n_stages + 1, sharex=True)
    others = [k for k in spec.columns if k != key]
    groups = _groups(rows, key, spec.columns)
    looks = _looks(groups)
    for i, (title, cols) in enumerate(families):
        for k in range(1, n_stages + 1):
            ax = axes[i][k - 1]
            for g, rs in groups.items():
                x = [_num(r.get(key)) for r in rs]
                colour, marker = looks[g]
                for c, style in cols.items():
                    label = " ".join(p for p in (_label(g, others), c.rsplit('_', 1)[-1] if len(cols) > 1 else "")
                                     if p)
                    ax.plot(x, [_num(r.get(f"stage{k}_{c}")) for r in rs], style, marker=marker, ms=4, lw=1,
                            color=colour, label=label)
            _pin_roundoff(ax, rows, [f"stage{k}_{c}" for c in cols])
            ax.set_title(f"stage {k}: {title}", fontsize=9)
            ax.grid(alpha=0.3)
    ax = axes[-1][0]
    for g, rs in groups.items():
        ax.plot([_num(r.get(key)) for r in rs], [_num(r.get("output_speed_rpm")) for r in rs], marker=looks[g][1],
                color=looks[g][0], label=_label(g, others))
    ax.set_title("output speed (rpm)", fontsize=9)
    ax.grid(alpha=0.3)
    for extra in axes[-1][1:]:
        extra.set_visible(False)
    lost = _mark_failed(axes, failed, key)
    axes[-1][0].set_xlabel(key)
    for k in range(1, n_stages):
        axes[-2][k].set_xlabel(key)
        axes[-2][k].xaxis.set_tick_params(labelbottom=True)
    handles, labels = axes[0][0].get_legend_handles_labels()
    if len(labels) > LEGEND_INSIDE:  # a grid's curves: a legend inside a 2-inch panel hid its title and its data
        _legend_below(fig, handles, labels, 2 * n_stages)
    else:
        axes[0][0].legend(fontsize=7, loc="best")
    _suptitle(fig, f"sweep response against {key}" + (f" (× on the axis: {lost} failed point{'s' if lost > 1 else ''})"
                                                      if lost else ""))
    return fig


def _mark_failed(axes, failed: Sequence[dict], key: str) -> int:
    """A × at the foot of every panel at each value of ``key`` where a point failed (it has no statistics to draw:
    left out, a sweep over teeth 21 and 4 whose 4 failed drew an axis of 21 alone, as if nothing else was asked);
    returns how many failed points have a numeric ``key``."""
    xs = [x for r in failed if np.isfinite(x := _num(r.get(key)))]
    if not xs:
        return 0
    for i, ax in enumerate(a for row in axes for a in row if a.get_visible()):
        ax.plot(xs, [0.0] * len(xs), ls="none", marker="x", ms=7, mew=1.5, color="tab:red", clip_on=False,
                transform=ax.get_xaxis_transform(), zorder=6, label="failed point" if i == 0 else None)
    return len(xs)


def _legend_below(fig, handles: list, labels: list[str], most: int) -> None:
    """The legend below the panels in as many columns (at most ``most``) as fit the figure's width: a key with a
    long path (``stage[0].mesh.transmission_error_um.0=2``) made two columns wider than a one-stage figure, whose
    legend then lost its labels' ends on both sides. One column wider than the figure widens the figure."""
    renderer = fig.canvas.get_renderer()
    for ncol in range(min(most, len(labels)), 0, -1):
        legend = fig.legend(handles, labels, loc="outside lower center", ncol=ncol, fontsize=7)
        width = legend.get_window_extent(renderer).width / fig.dpi  # inches
        if width <= fig.get_figwidth() - 0.2 or ncol == 1:
            break
        legend.remove()
    fig.set_figwidth(max(fig.get_figwidth(), width + 0.2))
    fig.set_figheight(fig.get_figheight() + 0.16 * -(-len(labels) // ncol) + 0.2)


def _pin_roundoff(ax, rows: Sequence[dict], cols: Sequence[str]) -> None:
    """A panel whose values differ only by roundoff (the rows of an unexcited scene are its equilibrium: std 0,
    dynamic factor 1, the same mean at every speed) is drawn as the constant it is, ±5 % of its scale (the
    values' magnitude, a std's or rms's the mean's, at least 1), without an offset; autoscaling would blow the
    last bits (1e-13 N) up to the panel's height."""
    limits = _roundoff_limits(rows, cols)
    if limits is None:
        return
    ax.set_ylim(*limits)
    ax.ticklabel_format(axis="y", useOffset=False, style="plain")


def _roundoff_limits(rows: Sequence[dict], cols: Sequence[str]) -> tuple[float, float] | None:
    """The axis limits of values that differ only by roundoff over ``rows`` and ``cols`` (:func:`_pin_roundoff`):
    the constant ±5 % of its scale (a non-negative family's from just below zero); None where they differ."""
    values = np.array([_num(r.get(c)) for r in rows for c in cols])
    values = values[np.isfinite(values)]
    if not values.size:
        return None
    refs = np.array([_num(r.get(c.replace(k, v))) for r in rows for c in cols for k, v in SCALE_OF.items()
                     if c.endswith(k)])
    scale = float(np.max(np.abs(np.concatenate([values, refs[np.isfinite(refs)], [1.0]]))))
    lo, hi = float(values.min()), float(values.max())
    if hi - lo > ROUNDOFF * scale:
        return None
    half = 0.05 * scale
    mid = 0.5 * (lo + hi)
    bottom = max(mid - half, -0.1 * half) if any(c.endswith(NON_NEGATIVE) for c in cols) else mid - half
    return bottom, mid + half


def _looks(groups: dict[tuple, list[dict]]) -> dict[tuple, tuple[Any, str]]:
    """Each curve's (colour, marker). One curve per direction: the direction's colour. Curves that differ in the
    other varied keys' values (a grid): a colour per combination of those values, the direction by its marker
    (up ^, down v), so that no two curves of one plot look alike."""
    combos = list(dict.fromkeys(g[1:] for g in groups))
    if len(combos) <= 1:
        return {g: (COLOURS.get(str(g[0]), "k"), ".") for g in groups}
    colours = _distinct_colours(len(combos))
    return {g: (colours[combos.index(g[1:])], MARKERS.get(str(g[0]), ".")) for g in groups}


def _distinct_colours(n: int) -> list:
    """``n`` colours, no two alike: the ten of matplotlib's cycle while they last; beyond them a sequential map
    in the combinations' order (the cycle's C0 ... C9 repeat: an 11-speed grid drew its 1st and 11th curves
    alike)."""
    if n <= 10:
        return [f"C{i}" for i in range(n)]
    from matplotlib import colormaps  # lazy: matplotlib, the optional plot extra (imported by the figure)
    return [tuple(c) for c in colormaps["viridis"](np.linspace(0.0, 0.9, n))]


def _label(group: tuple, others: Sequence[str]) -> str:
    """A curve's legend: its direction (up, down; none for independent points, where it says nothing) and the
    other varied keys' values."""
    extra = ", ".join(f"{k}={v}" for k, v in zip(others, group[1:], strict=True))
    direction = "" if str(group[0]) in ("none", "None") else str(group[0])
    return " ".join(p for p in (direction, f"({extra})" if extra else "") if p)


def _campbell(campbell: SweepCampbell):
    """The Campbell diagram of ``gearcli modes --plots`` (:mod:`gearcli.io.campbell`), over the swept range,
    with the swept speeds marked."""
    at = f"at {', '.join(campbell.at)}" if campbell.at else ""  # a grid: which point of the other keys it shows
    return campbell_io.campbell_figure(campbell.data, OutputUnits(*campbell.units), title=at,
                                       swept=list(campbell.swept_rpm))


def _bins(x: np.ndarray, panel: float = 0.0) -> dict:
    """The histogram's bins: up to 30, at least 5; one bar around a value every sample shares to rounding (an
    equilibrium's dynamic factor: 1 to the last bits, which no finite bins can split; a single sample), 4 % of
    the ``panel``'s span of values wide where the other curves give it one: 2e-6 of the value, on a panel that
    spans two stages' forces (4000 N to 10000 N), was a bar no pixel wide, an empty histogram."""
    width = float(x[-1] - x[0])
    scale = max(abs(float(x[0])), abs(float(x[-1])), 1e-300)
    if width <= 1e-9 * scale:
        half = max(1e-6 * scale, 0.02 * panel)
        return {"bins": 1, "range": (float(x[0]) - half, float(x[-1]) + half)}
    return {"bins": min(30, max(5, x.size // 5))}


def _ecdf(x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The empirical CDF of the sorted ``x`` as a post-step line: 0 below the first sample, i/n from the i-th on.
    It starts with the rise at the first sample (from 0 to 1/n), without which a single sample drew no line."""
    return np.concatenate([x[:1], x]), np.arange(0, x.size + 1) / x.size


def _pinned_bar(x: np.ndarray, limits: tuple[float, float]) -> dict:
    """One bar at the constant ``x`` shares to roundoff, 4 % of the pinned axis ``limits`` wide."""
    mid, width = 0.5 * float(x[0] + x[-1]), 0.02 * (limits[1] - limits[0])
    return {"bins": 1, "range": (mid - width, mid + width)}


def _distributions(rows: Sequence[dict], n_stages: int, grid: Sequence[str] = (), failed: int = 0):
    """Histograms and ECDFs of the random samples' statistics. With ``--vary`` keys too (``grid``: their columns)
    each point of the grid (and each direction) has its own distribution, drawn in its own colour: pooled, two operating speeds' samples made one two-humped histogram that no tolerance gives."""
    stats = [(c, t) for c, t in DISTRIBUTION_STATS if any(_has(rows, f"stage{k}_{c}") for k in range(1, n_stages + 1))]
    if not rows or not stats:
        return None
    groups: dict[tuple, list[dict]] = {}
    for r in rows:
        groups.setdefault(tuple(str(r.get(k)) for k in grid) + ((str(r.get("direction")),) if grid else ()),
                          []).append(r)
    labels = {g: _group_label(g, grid) for g in groups}
    curves = [(g, k) for g in groups for k in range(1, n_stages + 1)]
    colours = dict(zip(curves, _distinct_colours(len(curves)), strict=True))
    fig, axes = _figure(len(stats), 2, height=2.3, width=9.0)
    for i, (c, title) in enumerate(stats):
        # a statistic every sample shares to roundoff (an unexcited scene's std 0 and dynamic factor 1) is one bar
        # at its constant on an axis of ±5 % of its scale, as the response plot draws it, not its last bits
        pinned = _roundoff_limits(rows, [f"stage{k}_{c}" for k in range(1, n_stages + 1)])
        panel = np.array([_num(r.get(f"stage{k}_{c}")) for r in rows for k in range(1, n_stages + 1)])
        panel = panel[np.isfinite(panel)]
        span = float(np.ptp(panel)) if panel.size else 0.0
        for g, k in curves:
            x = np.array([_num(r.get(f"stage{k}_{c}")) for r in groups[g]])
            x = np.sort(x[np.isfinite(x)])
            if not x.size:
                continue
            bins = _bins(x, span) if pinned is None else _pinned_bar(x, pinned)
            label = ", ".join(p for p in (f"stage {k}" if n_stages > 1 or not labels[g] else "", labels[g]) if p)
            axes[i][0].hist(x, **bins, alpha=0.5, color=colours[(g, k)], label=label)
            axes[i][1].step(*_ecdf(x), where="post", color=colours[(g, k)], label=label)
        axes[i][0].set_xlabel(title)
        axes[i][0].set_ylabel("count")
        axes[i][1].set_xlabel(title)
        axes[i][1].set_ylabel("ECDF")
        for a in axes[i]:
            a.grid(alpha=0.3)
            if pinned is not None:
                a.set_xlim(*pinned)
                a.ticklabel_format(axis="x", useOffset=False, style="plain")
    if len(curves) > LEGEND_INSIDE:
        handles, names = axes[0][0].get_legend_handles_labels()
        _legend_below(fig, handles, names, 2)
    else:
        axes[0][0].legend(fontsize=7)
    per = max(len(rs) for rs in groups.values())
    title = (f"distributions over {_samples(len(rows))}" if len(groups) == 1 else
             f"distributions over {_samples(per)} at each of {len(groups)} grid points")
    # the samples that failed have no statistics: counted, so that "over 18 samples" of --samples 20 is explained
    _suptitle(fig, title + (f" ({failed} failed, not drawn)" if failed else ""))
    return fig


def _samples(n: int) -> str:
    return f"{n} random sample{'' if n == 1 else 's'}"


def _group_label(group: tuple, grid: Sequence[str]) -> str:
    """A grid point's legend in the distributions: ``input.speed_rpm=1200`` (and its direction, where continued)."""
    parts = [f"{k}={v}" for k, v in zip(grid, group, strict=False)]
    direction = group[len(grid)] if len(group) > len(grid) else "none"
    return ", ".join(parts + ([direction] if direction not in ("none", "None") else []))

