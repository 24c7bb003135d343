"""``gearcli report --plots DIR``: the Campbell diagram and four PNG figures, drawn with matplotlib's Agg canvas.

matplotlib is an optional extra (``pip install 'gearcli[plot]'``), imported by :mod:`gearcli.io.figures` inside
:func:`write_plots`; without it :class:`PlotsUnavailable` says how to install it. The figures use the
object-oriented API (``Figure`` + ``FigureCanvasAgg``), never pyplot, so no global backend state is
touched. Files are written atomically.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from gearcli.io import campbell as campbell_io
from gearcli.io.channels import named
from gearcli.io.figures import check as _figure_check
from gearcli.io.figures import figure as _figure
from gearcli.io.figures import save as _save
from gearcli.io.figures import suptitle as _suptitle
from gearcli.io.units import of_result
from gearcli.report.compare import driving_gear_factor
from gearcli.report.result import Report
from gearcli.stages.design import design_kind

if TYPE_CHECKING:  # matplotlib is imported when a figure is drawn (the plot extra)
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

FILES = ("speeds.png", "mesh_forces.png", "spectrum.png", "work_precision.png")


def _shade_window(ax, window) -> None:
    ax.axvspan(window[0], window[1], color="0.92", zorder=0, label="steady window")


def _zoom(ax, t: np.ndarray, y: np.ndarray, window, color: str) -> None:
    """The steady window alone, where the fluctuation is visible."""
    mask = (t >= window[0]) & (t <= window[1])
    ax.plot(t[mask], y[mask], lw=0.9, color=color)
    ax.set_xlim(window[0], window[1])
    if mask.any():  # head room for the legend above the trace
        lo, hi = float(np.min(y[mask])), float(np.max(y[mask]))
        pad = max(hi - lo, 1e-4 * max(abs(hi), 1.0))  # a constant trace gets a ±0.01 % band
        ax.set_ylim(lo - 0.08 * pad, hi + 0.45 * pad)
    ax.ticklabel_format(axis="y", useOffset=False)
    ax.grid(alpha=0.3)


def speeds_figure(r: Report) -> Figure:
    sim, shafts = r.simulation, r.design.shafts
    fig, axes = _figure(len(shafts), 2, sharex="col", height=1.8, width=12.0, width_ratios=(3, 2))

    u = of_result(sim)
    for (ax, zoom), shaft in zip(axes, shafts, strict=True):
        series = named(sim).get(f"shaft{shaft.index}_speed_deg_s")
        _shade_window(ax, sim.window_s)
        if series is not None:
            series = u.speed_from_deg_s(series)
            ax.plot(sim.time_s, series, lw=1.0, color="C0", label="simulated")
            _zoom(zoom, sim.time_s, series, sim.window_s, "C0")
        design_speed = u.speed_from_deg_s(shaft.speed_deg_s)
        for a in (ax, zoom):
            a.axhline(design_speed, ls="--", lw=1.0, color="k", label=f"design {design_speed:.5g} {u.speed_label}")
        name = "input" if shaft.index == 1 else ("output" if shaft.index == len(shafts) else "intermediate")
        ax.set_ylabel(f"shaft {shaft.index}\n[{u.speed_label}]")
        ax.set_title(f"shaft {shaft.index} ({name})", fontsize=9, loc="left")
        zoom.set_title(f"shaft {shaft.index}, steady window", fontsize=9, loc="left")
        ax.legend(loc="lower right", fontsize=8)
        ax.grid(alpha=0.3)
    axes[-1, 0].set_xlabel("time [s]")
    axes[-1, 1].set_xlabel("time [s]")
    _suptitle(fig, f"Shaft speeds — {r.title or 'design'}")
    return fig


def mesh_forces_figure(r: Report) -> Figure:
    sim = r.simulation
    fig, axes = _figure(len(r.stages), 2, sharex="col", height=2.1, width=12.0, width_ratios=(3, 2))
    factors = {st.index: driving_gear_factor(st, design_kind(st).model_signs_forces) for st in r.design.stages}
    for (ax, zoom), s in zip(axes, r.stages, strict=True):
        series = named(sim).get(f"stage{s.stage}_tangential_N")
        color = f"C{(s.stage - 1) % 10}"
        _shade_window(ax, sim.window_s)
        if series is not None:
            ax.plot(sim.time_s, series, lw=0.8, color=color, label="F_t simulated")
            _zoom(zoom, sim.time_s, series, sim.window_s, color)
        static = (s.static_tangential_N * factors.get(s.stage, 1.0)  # the comparison's theory (the driving member's,
                  * (r.theory_point.load_factor if r.theory_point is not None else 1.0))  # at the operating point)
        for a in (ax, zoom):
            a.axhline(static, ls="--", lw=1.2, color="k", label=f"static F_t {static:.5g} N")
        zoom.axhline(s.tangential_N.mean, ls=":", lw=1.2, color="C3", label=f"mean {s.tangential_N.mean:.5g} N")
        ax.plot([s.peak_time_s], [_signed_peak(sim.time_s, series, s.peak_time_s, s.peak_tangential_N)], "v",
                color="C3", ms=6,
                label=f"run-up peak {s.peak_tangential_N:.5g} N"
                + (f" (run-up factor {s.runup_factor:.3g})" if s.runup_factor is not None else ""))
        ax.set_ylabel("F_t [N]")
        ax.set_title(f"stage {s.stage}: tangential mesh force", fontsize=9, loc="left")
        zoom.set_title(f"stage {s.stage}, steady window (std {s.tangential_N.std:.3g} N)", fontsize=9, loc="left")
        ax.legend(loc=_clear_corner(ax, s.tangential_N.mean), fontsize=8)
        zoom.legend(loc="upper right", fontsize=8)
        ax.grid(alpha=0.3)
    axes[-1, 0].set_xlabel("time [s]")
    axes[-1, 1].set_xlabel("time [s]")
    fig.suptitle("Tangential mesh forces (dashed: static theory)", fontsize=11)
    return fig


def _clear_corner(ax, steady_level: float) -> str:
    """The right-hand corner the steady trace leaves free: it runs along the right half of the panel at its steady
    level, so a loaded train's forces (at the top) take the legend below them, a reversed load's above them."""
    lo, hi = ax.get_ylim()
    return "lower right" if steady_level > 0.5 * (lo + hi) else "upper right"


def _signed_peak(time_s: np.ndarray, series: np.ndarray | None, at_s: float | None, peak_N: float) -> float:
    """The run-up peak |F_t| with the sign the force has there (a reversed load's forces are negative: the marker
    belongs on the curve, not mirrored above it)."""
    if series is None or at_s is None or len(time_s) == 0:
        return peak_N
    value = series[int(np.argmin(np.abs(np.asarray(time_s) - at_s)))]
    return -abs(peak_N) if value < 0 else abs(peak_N)


def spectrum_figure(r: Report) -> Figure:
    fig, axes = _figure(len(r.stages), sharex=True, height=2.0)
    natural = [f for f in r.natural_frequencies_Hz if f > 0]
    for ax, s in zip(axes[:, 0], r.stages, strict=True):
        sp = s.spectrum
        if sp.frequency_Hz.size > 1:
            amp = np.where(sp.amplitude_N > 0, sp.amplitude_N, np.nan)
            ax.semilogy(sp.frequency_Hz[1:], amp[1:], lw=0.9, color=f"C{s.stage - 1}", label="|F_t| amplitude")
        ax.axvline(sp.mesh_frequency_Hz, color="k", ls="--", lw=1.2, label=f"mesh {sp.mesh_frequency_Hz:.4g} Hz")
        for j, fn in enumerate(f for f in natural if f <= sp.nyquist_Hz):
            ax.axvline(fn, color="C3", ls=":", lw=1.2, label="natural frequencies" if j == 0 else None)
        if sp.peak_frequency_Hz is not None:
            on_curve = sp.amplitude_N[int(np.argmin(np.abs(sp.frequency_Hz - sp.peak_frequency_Hz)))]
            ax.plot([sp.peak_frequency_Hz], [on_curve], "o", mfc="none", color="k", ms=7,  # the bin on the curve
                    label=f"peak {sp.peak_frequency_Hz:.4g} ± {sp.resolution_Hz:.2g} Hz")
        ax.set_ylabel("amplitude [N]")
        ax.set_title(f"stage {s.stage}", fontsize=9, loc="left")
        ax.legend(loc="upper right", fontsize=8)
        ax.grid(alpha=0.3, which="both")
    if r.stages:
        sp = r.stages[0].spectrum
        axes[-1, 0].set_xlim(0, _spectrum_xmax(r))
        fig.suptitle(f"F_t spectrum over the steady window {sp.window_s[0]:.3g}–{sp.window_s[1]:.3g} s "
                     f"({'whole periods, less the mean' if sp.whole_periods else 'Hann, detrended'}; "
                     f"resolution {sp.resolution_Hz:.2g} Hz)", fontsize=11)
    axes[-1, 0].set_xlabel("frequency [Hz]")
    return fig


def _spectrum_xmax(r: Report) -> float:
    """2.5 times the highest line of interest (mesh frequency, natural frequency, peak), within Nyquist."""
    nyq = r.stages[0].spectrum.nyquist_Hz
    lines = [s.spectrum.mesh_frequency_Hz for s in r.stages] + list(r.natural_frequencies_Hz)
    lines += [s.spectrum.peak_frequency_Hz or 0.0 for s in r.stages]
    lines = [f for f in lines if 0 < f <= nyq]
    return min(nyq, 2.5 * max(lines)) if lines and nyq > 0 else (nyq or 1.0)


ERROR_PANELS = (("speed", "mean output speed"), ("mean_force", "mean F_t (worst stage)"),
                ("peak_force", "run-up peak F_t (worst stage)"))


def work_precision_figure(r: Report) -> Figure:
    study = r.accuracy
    assert study is not None, "work_precision.png needs the accuracy study"
    fig, axes = _figure(1, 3, sharey=True, height=3.9, width=12.5)
    methods = list(dict.fromkeys(run.method for run in study.runs))
    unc = study.reference.uncertainty
    ok = [x for x in study.runs if x.failure is None]
    errors = [e for x in ok for q, _ in ERROR_PANELS if (e := x.error(q))] + [unc, study.requested_accuracy]
    low, high = min(e for e in errors if e > 0) / 4, max(errors) * 3
    for ax, (q, title) in zip(axes[0], ERROR_PANELS, strict=True):
        for i, m in enumerate(methods):
            runs = sorted((x for x in ok if x.method == m and x.error(q)), key=lambda x: x.rtol, reverse=True)
            if not runs:
                continue
            label = m if m == runs[0].method_used else f"{m} ({runs[0].method_used})"
            ax.loglog([x.wall_s for x in runs], [x.error(q) for x in runs], "o-", color=f"C{i}", ms=4, lw=1.2,
                      label=label)
            if i == 0:  # the rtol of each rung, on the first method's line
                for x in runs:
                    ax.annotate(f"{x.rtol:.0e}", (x.wall_s, x.error(q)), textcoords="offset points",
                                xytext=(4, 3), fontsize=6.5, color=f"C{i}")
        ax.axhline(study.requested_accuracy, color="k", ls="--", lw=1.0,
                   label=f"target {study.requested_accuracy:g}")
        resolution = study.reference.resolution(q)  # this quantity's: its difference from the check run
        ax.axhspan(low, max(resolution, low), color="0.85", zorder=0,
                   label="below the reference's resolution of the quantity")
        _mark(ax, study.recommended, q, "*", "recommended (cheapest meeting the target)", 15)
        _mark(ax, study.file_run, q, "s", "the file's settings", 10)
        ax.set_ylim(low, high)
        log_ticks(ax)
        ax.set_title(f"error of the {title} (resolution {resolution:.1e})", fontsize=9)
        ax.set_xlabel("wall time [s]")
        ax.grid(alpha=0.3, which="both")
    axes[0, 0].set_ylabel("relative error against the reference")
    handles, labels = axes[0, 0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="outside lower center", ncol=4, fontsize=8)
    ref = study.reference
    fig.suptitle(f"Work against precision — reference {ref.method} rtol {ref.rtol:g}, checked with "
                 f"{ref.check_method} rtol {ref.check_rtol:g} (uncertainty {unc:.1e})", fontsize=11)
    return fig


def log_ticks(ax: Axes) -> None:
    """Labels on a logarithmic x axis that do not run into each other: plain numbers (0.002, 0.005, 0.01) at 1-9,
    1-2-5 or 1 of each decade as the axis spans under half a decade, under 1.5 or more, and no labelled minor ticks
    (matplotlib labels them on an axis short of a decade, and on a panel a third of the page wide
    "2x10^-3 3x10^-3 4x10^-3" overlapped)."""
    from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter  # lazy: the optional plot extra

    lo, hi = ax.get_xlim()
    decades = float(np.log10(hi / lo)) if lo > 0 and hi > lo else 1.0
    subs = tuple(range(1, 10)) if decades < 0.5 else (1, 2, 5) if decades < 1.5 else (1,)
    ax.xaxis.set_major_locator(LogLocator(base=10.0, subs=subs))
    ax.xaxis.set_major_formatter(FuncFormatter(lambda v, _pos: f"{v:g}"))
    ax.xaxis.set_minor_formatter(NullFormatter())


def _mark(ax, run, q: str, marker: str, label: str, size: float) -> None:
    if run is not None and run.failure is None and run.error(q):
        ax.plot([run.wall_s], [run.error(q)], marker, mfc="none", mec="k", ms=size, label=label)


FIGURE_NAMES = ("campbell.png", "speeds.png", "mesh_forces.png", "spectrum.png", "work_precision.png")


def write_plots(r: Report, directory: str | Path) -> list[Path]:
    """Write the figures into ``directory`` (created if needed); returns the paths written.
    ``work_precision.png`` needs the accuracy study, so it is left out with ``--quick``."""
    out = Path(directory)
    figures = [("speeds.png", speeds_figure), ("mesh_forces.png", mesh_forces_figure),
               ("spectrum.png", spectrum_figure)]
    if r.accuracy is not None:
        figures.append(("work_precision.png", work_precision_figure))
    _figure_check()
    out.mkdir(parents=True, exist_ok=True)
    written = []
    if r.campbell is not None:  # the engineering figure first
        written.append(_save(campbell_io.campbell_figure(r.campbell, of_result(r.simulation), r.title), out / "campbell.png"))
    return written + [_save(make(r), out / name) for name, make in figures]
