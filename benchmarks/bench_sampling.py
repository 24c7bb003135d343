"""Sampling error of the window min/max of F_t: the estimate (gearcli/simulate/sampling.py) against the truth.

The truth is the same run sampled FINE times finer: the solver takes the same steps whatever the output
samples (the samples read its dense output), so the difference of the extremes is the sampling error alone.
Usage: PYTHONPATH=$PWD python benchmarks/bench_sampling.py [configs ...] [--fine 16]
"""

from __future__ import annotations

import argparse
import sys

import numpy as np

from gearcli import api
from gearcli.core.channels import Channel
from gearcli.simulate.sampling import extremes_error
from gearcli.simulate.stats import window_mask

DEFAULT = ["configs/concrete_mixer_te.toml", "configs/backlash_oscillator.toml",
           "configs/mixer_time_varying_backlash.toml", "configs/wind_turbine_gearbox.toml", "configs/conveyor.toml",
           "configs/conveyor_periodic.toml", "configs/spur_oscillator_te.toml", "configs/concrete_mixer.toml"]


def run(path: str, steps: int | None, method: str | None = None):
    sets = [f"simulation.steps={steps}"] if steps else []
    if method:
        sets.append(f"simulation.method={method}")
    loaded = api.load(path, sets)
    return loaded.cfg, api.simulate(loaded.cfg, api.design(loaded), error_estimate=False)


def main() -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("configs", nargs="*", default=DEFAULT)
    ap.add_argument("--fine", type=int, default=16)
    a = ap.parse_args()
    print("| config | stage | samples/window | ref N | min: est / true | max: est / true |")
    print("|---|---|---|---|---|---|")
    for path in a.configs:
        cfg, coarse = run(path, None)
        periodic = cfg.simulation.steady == "periodic"
        _, fine = run(path, cfg.simulation.steps * a.fine, coarse.solver.method)
        for k, st in enumerate(coarse.stages):
            ch = Channel("tangential_force", f"stage{k + 1}")
            m = window_mask(coarse.time_s, coarse.window_s)
            if periodic:
                m &= coarse.time_s < coarse.window_s[1] - 1e-12
            t, x = coarse.time_s[m], coarse.series[ch][m]
            est_min, est_max = extremes_error(t, x, periodic=periodic)
            fs = fine.stages[k].tangential_N
            ref = abs(st.tangential_N.mean) or 1.0
            tmin, tmax = st.tangential_N.min - fs.min, fs.max - st.tangential_N.max
            print(f"| {path} | {k + 1} | {m.sum()} | {ref:.4g} | {est_min / ref:.2e} / {tmin / ref:.2e} | "
                  f"{est_max / ref:.2e} / {tmax / ref:.2e} |", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
