"""Sampling error of the window min/max of F_t: the estimate (gearcli/simulate/sampling.py) against the truth.

The truth is the same run sampled FINE times finer: the solver takes the same steps whatever the output
samples (the samples read its dense output), so the difference of the extremes is the sampling error alone.
The estimate is the reported one (SAFETY x the interpolated excess). std and the spectrum's dominant line: their
change between the two samplings (no estimate: measured to decide whether they need one).
Usage: PYTHONPATH=$PWD python benchmarks/bench_sampling.py [configs ...] [--fine 16]
"""

from __future__ import annotations

import argparse
import sys

import numpy as np

from gearcli import api
from gearcli.core.channels import Channel
from gearcli.simulate import run_simulation
from gearcli.simulate.estimate import spectrum
from gearcli.simulate.sampling import SAFETY, extremes_error
from gearcli.simulate.stats import window_mask

DEFAULT = ["configs/concrete_mixer_te.toml", "configs/backlash_oscillator.toml",
           "configs/mixer_time_varying_backlash.toml", "configs/wind_turbine_gearbox.toml", "configs/conveyor.toml",
           "configs/conveyor_periodic.toml", "configs/spur_oscillator_te.toml", "configs/concrete_mixer.toml"]


def run(path: str, steps: int | None, method: str | None = None):
    sets = [f"simulation.steps={steps}"] if steps else []
    if method:
        sets.append(f"simulation.method={method}")
    loaded = api.load(path, sets)
    return loaded.design, run_simulation(loaded.design, api.design(loaded), error_estimate=False)


def _window(result, ch, periodic: bool):
    m = window_mask(result.time_s, result.window_s)
    if periodic:  # whole periods without their closing sample
        m &= result.time_s < result.window_s[1] - 1e-9 * result.window_s[1]
    return result.time_s[m], result.series[ch][m]


def main() -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("configs", nargs="*", default=DEFAULT)
    ap.add_argument("--fine", type=int, default=16)
    a = ap.parse_args()
    print("| config | stage | samples/window | ref N | min: est / true | max: est / true | std: true | spectrum peak: true |")
    print("|---|---|---|---|---|---|---|---|")
    for path in a.configs:
        cfg, first = run(path, None)
        periodic = cfg.simulation.steady == "periodic"
        # both with the method auto chose (auto may change course mid-run: the same steps need the same method)
        _, coarse = run(path, cfg.simulation.steps, first.solver.method)
        _, fine = run(path, cfg.simulation.steps * a.fine, first.solver.method)
        for k, st in enumerate(coarse.stages):
            ch = Channel("tangential_force", f"stage{k + 1}")
            t, x = _window(coarse, ch, periodic)
            est_min, est_max = extremes_error(t, x, periodic=periodic)
            xf = _window(fine, ch, periodic)[1]
            ref = abs(st.tangential_N.mean) or 1.0
            tmin, tmax = x.min() - xf.min(), xf.max() - x.max()
            tf, xf = _window(fine, ch, periodic)
            tstd = abs(x.std() - xf.std())
            fa, aa = spectrum(t, x)
            fb, ab = spectrum(tf, xf)
            j = 1 + int(np.argmax(aa[1:]))  # the coarse spectrum's dominant line, read at its frequency in the fine one
            tspec = abs(aa[j] - np.interp(fa[j], fb, ab))
            print(f"| {path} | {k + 1} | {t.size} | {ref:.4g} | {SAFETY * est_min / ref:.2e} / {tmin / ref:.2e} | "
                  f"{SAFETY * est_max / ref:.2e} / {tmax / ref:.2e} | {tstd / ref:.1e} | {tspec / ref:.1e} |", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
