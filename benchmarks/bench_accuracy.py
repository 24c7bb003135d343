"""Honesty of the default statistics on every scene of configs/ and configs/extreme/ (docs/performance.md).

    PYTHONPATH=$PWD python benchmarks/bench_accuracy.py [--only NAME ...] [--markdown]

For each scene: the default run (with its error estimate) against a reference of the same scene at rtol
1e-10 with the run's method (DOP853 at rtol 1e-8 where that is too slow: stiff_linear_10000x). Columns:
the largest true error of min/max/std of any stage's F_t (relative to the mean), the largest estimated
one, whether the run warns ``statistics_unresolved``, whether a statistic beyond 1e-3 went unwarned
("missed", must be 0), and the cost: evaluations of the run and of its check pass, and the ratio of the
whole to the run without the estimate (today's cost before the estimate existed).
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from gearcli import diagnostics as dg  # noqa: E402
from gearcli.config import load_design  # noqa: E402
from gearcli.design import compute_design  # noqa: E402
from gearcli.simulate import run_simulation  # noqa: E402
from gearcli.simulate.estimate import TARGET  # noqa: E402

QS = ("min", "max", "std")
REFERENCE = {"stiff_linear_10000x": ("DOP853", 1e-8)}


def row(path: Path) -> dict:
    cfg = load_design(str(path), []).design
    design = compute_design(cfg)
    t0 = time.perf_counter()
    base = run_simulation(cfg, design, want_series=False, error_estimate=False)
    wall_base = time.perf_counter() - t0
    t0 = time.perf_counter()
    sim = run_simulation(cfg, design, want_series=False)
    wall = time.perf_counter() - t0
    method, rtol = REFERENCE.get(path.stem, (sim.solver.method, 1e-10))
    ref = run_simulation(cfg, design, method=method, rtol=rtol, want_series=False, error_estimate=False,
                         max_nfev=20_000_000)
    true = est = 0.0
    missed = 0
    warned = {d.data["stage"]: set(d.data["statistics"]) for d in sim.diagnostics if d.code == dg.STATISTICS_UNRESOLVED}
    for s, r in zip(sim.stages, ref.stages, strict=True):
        scale = abs(r.tangential_N.mean) or 1.0
        for q in QS:
            e = abs(getattr(s.tangential_N, q) - getattr(r.tangential_N, q)) / scale
            true = max(true, e)
            if e > TARGET and q not in warned.get(s.index, set()):
                missed += 1
        if s.error_estimate is not None:
            est = max(est, *(s.error_estimate.relative[q] for q in QS))
    check = sim.solver.check_pass or {}
    return {"scene": f"{path.parent.name}/{path.stem}", "method": sim.solver.method, "true": true, "estimated": est,
            "warned": bool(warned), "missed": missed, "nfev": base.solver.nfev, "check_nfev": check.get("nfev", 0),
            "check_rtol": check.get("rtol", 0.0), "passes": check.get("passes", 1), "from_s": check.get("from_s", 0.0),
            "cost": (sim.solver.nfev + check.get("nfev", 0)) / base.solver.nfev, "wall_ratio": wall / wall_base}


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--only", nargs="*", default=None)
    args = ap.parse_args()
    paths = sorted((ROOT / "configs").glob("*.toml")) + sorted((ROOT / "configs" / "extreme").glob("*.toml"))
    print("| scene | method | true error (min/max/std) | estimated | warned | missed | nfev run + check "
          "| check rtol, from | cost (nfev) | cost (wall) |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for p in paths:
        if args.only and p.stem not in args.only:
            continue
        try:
            r = row(p)
        except Exception as exc:  # noqa: BLE001 - a failing scene is a row, not the end of the table
            print(f"| {p.parent.name}/{p.stem} | failed: {type(exc).__name__} | | | | | | | | |", flush=True)
            continue
        print(f"| {r['scene']} | {r['method']} | {r['true']:.1e} | {r['estimated']:.1e} | {'yes' if r['warned'] else 'no'} "
              f"| {r['missed']} | {r['nfev']} + {r['check_nfev']} | {r['check_rtol']:.0e}, {r['from_s']:.3g} s "
              f"| {r['cost']:.2f}x | {r['wall_ratio']:.2f}x |", flush=True)


if __name__ == "__main__":
    main()
