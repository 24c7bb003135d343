"""Calibrate the cost model (gearcli/core/cost.py): counters and wall time of both methods on both engines.

    PYTHONPATH=$PWD python benchmarks/bench_cost.py [--only NAME ...] [--python-budget 300000] [--json FILE]

For every scene of ``bench_auto.scenes()`` (configs/, configs/extreme/, the excitation scenes, the conveyor),
DOP853 and Radau at the file's rtol (no error estimate), on the compiled engine and on scipy (the Python runs
within ``--python-budget`` evaluations; a run beyond it is left out of the fit): nfev, njev, nlu, accepted steps,
the integration's wall time, and what the cost model predicted (evaluations of each method). Then per engine a
non-negative least-squares fit of the wall time against the counters (the prices of ``cost.PRICE_S``), the
measured counters per evaluation of Radau (``cost.COUNTERS_PER_EVAL``), and the ratio of measured to predicted
evaluations per scene and method (what ``cost.predicted_evaluations`` should meet; the run is timed on one
core of a shared machine, so the fit weighs every run by 1 / its wall time: relative errors).
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import numpy as np
from scipy.optimize import nnls

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "benchmarks"))

from bench_auto import scenes  # noqa: E402

from gearcli import engine  # noqa: E402
from gearcli.config import load_design  # noqa: E402
from gearcli.design import compute_design  # noqa: E402
from gearcli.errors import GearcliError  # noqa: E402
from gearcli.scene import spec_from_design  # noqa: E402
from gearcli.simulate import run_simulation  # noqa: E402
from gearcli.simulate.choice import choose_method  # noqa: E402

COUNTERS = ("nfev", "njev", "nlu", "steps_explicit", "steps_implicit")


def one(cfg, design, method: str, eng: str, budget: int) -> dict | None:
    cfg = cfg.model_copy(update={"simulation": cfg.simulation.model_copy(update={"engine": eng})})
    try:
        sim = run_simulation(cfg, design, method=method, want_series=False, max_nfev=budget, error_estimate=False)
    except GearcliError:
        return None
    s = sim.solver
    implicit = method == "Radau"
    return {"wall_s": s.wall_s, "nfev": s.nfev, "njev": s.njev, "nlu": s.nlu,
            "steps_explicit": 0 if implicit else s.steps, "steps_implicit": s.steps if implicit else 0}


def fit(rows: list[dict]) -> dict[str, float]:
    A = np.array([[r[c] for c in COUNTERS] for r in rows], dtype=float)
    b = np.array([r["wall_s"] for r in rows])
    w = 1.0 / np.maximum(b, 1e-3)
    x, _ = nnls(A * w[:, None], b * w)
    return dict(zip(COUNTERS, (float(v) for v in x), strict=True))


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--only", nargs="*")
    ap.add_argument("--python-budget", type=int, default=300_000)
    ap.add_argument("--json")
    args = ap.parse_args()
    engine.load()
    out = []
    for name, path, sets in scenes():
        if args.only and not any(o in name for o in args.only):
            continue
        cfg = load_design(str(path), sets).design
        design = compute_design(cfg)
        spec = spec_from_design(cfg, design)
        c = choose_method(spec, cfg.simulation.duration_s, "auto", cfg.simulation.rtol)
        row = {"scene": name, "predicted": list(c.predicted_evals), "indicator": c.indicator,
               "vibration_rad": c.vibration_rad, "excited_rad": c.excited_rad}
        for m in ("DOP853", "Radau"):
            row[f"{m}/compiled"] = one(cfg, design, m, "compiled", 5_000_000)
            row[f"{m}/python"] = one(cfg, design, m, "python", args.python_budget)
        out.append(row)
        cells = []
        for k, m in enumerate(("DOP853", "Radau")):
            r = row[f"{m}/compiled"]
            cells.append(f"{m} {r['nfev'] if r else '-':>8} ({r['nfev'] / row['predicted'][k] if r else 0:5.2f}x pred)")
        print(f"{name:42s} " + "  ".join(cells), flush=True)
    for eng in ("compiled", "python"):
        runs = [r[f"{m}/{eng}"] for r in out for m in ("DOP853", "Radau") if r.get(f"{m}/{eng}")]
        if runs:
            prices = fit(runs)
            print(f"{eng}: " + ", ".join(f"{k} {v * 1e6:.3g} us" for k, v in prices.items()))
        radau = [r[f"Radau/{eng}"] for r in out if r.get(f"Radau/{eng}")]
        if radau:
            n = sum(r["nfev"] for r in radau)
            print(f"  Radau per evaluation: steps {sum(r['steps_implicit'] for r in radau) / n:.3f}, "
                  f"lu {sum(r['nlu'] for r in radau) / n:.3f}, jac {sum(r['njev'] for r in radau) / n:.4f}")
    if args.json:
        Path(args.json).write_text(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
