"""``gearcli life --plots DIR``: the load spectra against the S–N curves (pitting.png, bending.png).

Each panel is one stage: the S–N curve of each member (stress against cycles to failure, log–log; the curve
of the duty's first point) and the member's cumulative stress spectrum (load classes sorted by stress, the
cycles at or above each stress), as in ISO 6336-6's figures.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from gearcli.io.figures import check as _check
from gearcli.io.figures import figure as _figure
from gearcli.io.figures import save as _save
from gearcli.life.miner import SNCurve
from gearcli.life.result import LifeResult, member_label

FIGURE_NAMES = ("pitting.png", "bending.png")
COLORS = {"pinion": "tab:blue", "gear": "tab:orange", "ring": "tab:red", "planet_ring_side": "tab:green",
          "planet_root": "tab:purple"}


def _mode_life(st, member: str, mode: str):
    """The member's life in ``mode`` (None where it has none): ``planet_root`` is the planet's root bending over both
    meshes (docs/life.md: the figure to judge a planet's root by), bending only."""
    life = getattr(st, member)
    if member == "planet_root":
        return life if mode == "bending" else None
    return None if life is None else getattr(life, mode)


def write_life_plots(r: LifeResult, plots_dir: str) -> list[Path]:
    """Both figures into ``plots_dir`` (created if missing), each written atomically; without matplotlib
    :class:`~gearcli.io.figures.PlotsUnavailable` before the directory is made."""
    _check()
    out_dir = Path(plots_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    paths = []
    for mode, name in zip(("pitting", "bending"), FIGURE_NAMES, strict=True):
        fig, axes = _figure(len(r.stages), 1, height=2.8)
        for ax, st in zip(axes[:, 0], r.stages, strict=True):
            members = [m for m in COLORS if _mode_life(st, m, mode) is not None]  # a planetary stage's ring mesh too
            first = min(_first_cycles(_mode_life(st, m, mode).bins) for m in members)
            for member in members:
                label = member_label(st, member)
                ml = _mode_life(st, member, mode)
                curve: SNCurve = ml.sn
                bins = sorted(ml.bins, key=lambda b: -b.stress_MPa)
                cum = np.cumsum([b.cycles for b in bins])  # cycles at or above each class's stress
                n = np.logspace(np.log10(first), 12, 200)
                ax.loglog(n, [curve.stress_at(x) for x in n], color=COLORS[member],
                          lw=3.0 if member == "pinion" else 1.2, alpha=0.5 if member == "pinion" else 1.0,
                          label=f"{label} S–N")
                ax.step([first, *cum], [bins[0].stress_MPa, *(b.stress_MPa for b in bins)], where="pre",
                        color=COLORS[member], ls="--", lw=1.2, label=f"{label} spectrum (D = {ml.damage:.3g})")
            ax.set_title(f"stage {st.index}: {mode}", fontsize=9)
            ax.set_ylabel("σ_H [MPa]" if mode == "pitting" else "σ_F [MPa]")
            ax.grid(True, which="both", alpha=0.3)
            # beside the axes: inside, up to ten entries (a planetary stage's) covered the S–N curves past the knee
            ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0)
        axes[-1, 0].set_xlabel("load cycles")
        paths.append(_save(fig, out_dir / name))
    return paths


def _first_cycles(bins) -> float:
    """Where the cycle axis starts: 1e3 cycles, or a decade below the highest-stress class's cycles where it has
    fewer (a start's peak classes: some tens of cycles). The cumulative spectrum's top step runs from there to its
    cycles; from a fixed 1e3 it ran backwards, drawing 1e3 cycles at a start's peak stress where the duty has 40."""
    top = max(bins, key=lambda b: b.stress_MPa).cycles if bins else 1e3
    return min(1e3, 10.0 ** (np.floor(np.log10(top)) - 1.0)) if top > 0 else 1e3
