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
COLORS = {"pinion": "tab:blue", "gear": "tab:orange", "ring": "tab:red", "planet_ring_side": "tab:green"}


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
            members = [m for m in COLORS if getattr(st, m) is not None]  # a planetary stage's ring mesh too
            for member in members:
                label = member_label(st, member)
                ml = getattr(getattr(st, member), mode)
                curve: SNCurve = ml.sn
                n = np.logspace(3, 12, 200)
                ax.loglog(n, [curve.stress_at(x) for x in n], color=COLORS[member],
                          lw=3.0 if member == "pinion" else 1.2, alpha=0.5 if member == "pinion" else 1.0,
                          label=f"{label} S–N")
                bins = sorted(ml.bins, key=lambda b: -b.stress_MPa)
                cum = np.cumsum([b.cycles for b in bins])  # cycles at or above each class's stress
                ax.step([n[0], *cum], [bins[0].stress_MPa, *(b.stress_MPa for b in bins)], where="pre",
                        color=COLORS[member], ls="--", lw=1.2, label=f"{label} spectrum (D = {ml.damage:.3g})")
            ax.set_title(f"stage {st.index}: {mode}", fontsize=9)
            ax.set_ylabel("σ_H [MPa]" if mode == "pitting" else "σ_F [MPa]")
            ax.grid(True, which="both", alpha=0.3)
            ax.legend(fontsize=7, loc="upper right")
        axes[-1, 0].set_xlabel("load cycles")
        paths.append(_save(fig, out_dir / name))
    return paths
