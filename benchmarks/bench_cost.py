"""Calibrate the cost model (gearcli/core/cost.py) on one set of scenes and judge it on another.

    PYTHONPATH=$PWD python benchmarks/bench_cost.py [--only NAME ...] [--python-budget 300000] [--json FILE]
                                                     [--set fit|held-out|all]

Scenes (:func:`scene_sets`): the **fitting set**, configs/ and configs/extreme/ less the held-out files; the
**held-out set**, files the fit never sees (a drivetrain, a planetary gearbox, motor starts, excited, stiff
and rattling scenes) and variants of them a seeded generator draws (the ISO-calibrated Hertz mesh law with 5 %
viscous damping that scenes without [contact] get, a tighter rtol, a longer or shorter run).

For every scene, DOP853 and Radau at the file's rtol (no error estimate), on the compiled engine and on scipy
(the Python runs within ``--python-budget`` evaluations): nfev, njev, nlu, steps, the integration's wall time,
the model's size (:class:`gearcli.core.cost.ModelSize`) and auto's predicted evaluations. The time is the CPU
time of the integration (the process's): on the shared 2-core machine the wall clock runs 2-10x slower whenever
other jobs run, and a price fitted to it would price the neighbours' load. Then per engine and
method a non-negative least-squares fit over the fitting set of

    wall = run fixed cost + nfev x (price per evaluation = coefficients . ModelSize.features())

(``cost.RUN_FIXED_S``, ``cost.PRICE_US``; weighted by 1 / wall: relative errors), and on both sets, with the
fitted prices, the ratio of measured to predicted evaluations and time, scene by scene (docs/performance.md).
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np
from scipy.optimize import nnls

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "benchmarks"))

from scenes import scene_sets  # noqa: E402

from gearcli import engine  # noqa: E402
from gearcli.config import load_design  # noqa: E402
from gearcli.core import cost  # noqa: E402
from gearcli.design import compute_design  # noqa: E402
from gearcli.errors import GearcliError  # noqa: E402
from gearcli.scene import spec_from_design  # noqa: E402
from gearcli.simulate import course, run_simulation  # noqa: E402
from gearcli.simulate.choice import choose_method  # noqa: E402

METHODS = ("DOP853", "Radau")


_CPU = {"s": 0.0}


def _timed_integrate(*args, **kwargs):
    """course.integrate, its CPU time added up (the process's, all its threads: the compiled kernel runs in a worker
    thread, gearcli.simulate.solver; CPU time, so that a shared machine's load does not inflate it)."""
    t0 = time.process_time()
    try:
        return _INTEGRATE(*args, **kwargs)
    finally:
        _CPU["s"] += time.process_time() - t0


_INTEGRATE = course.integrate
course.integrate = _timed_integrate


def one(cfg, design, method: str, eng: str, budget: int) -> dict | None:
    """One run; ``wall_s`` is the CPU time of its integration (what the price per evaluation predicts on an idle
    machine; the wall clock of this shared 2-core machine runs 2-10x slower under other jobs)."""
    cfg = cfg.model_copy(update={"simulation": cfg.simulation.model_copy(update={"engine": eng})})
    _CPU["s"] = 0.0
    try:
        sim = run_simulation(cfg, design, method=method, want_series=False, max_nfev=budget, error_estimate=False)
    except GearcliError:
        return None
    s = sim.solver
    if s.course_changes or s.engine != eng:
        return None
    return {"wall_s": _CPU["s"], "clock_s": s.wall_s, "nfev": s.nfev, "njev": s.njev, "nlu": s.nlu,
            "steps": s.steps}


def fit_prices(rows: list[dict], key: str) -> tuple[float, tuple[float, ...]]:
    """(run fixed seconds, price coefficients in us) of wall = fixed + nfev x coefficients . features."""
    runs = [(r["features"], r[key]) for r in rows if r.get(key) and r[key]["wall_s"] > 0]  # a periodic run: untimed
    A = np.array([[1.0] + [run["nfev"] * f * 1e-6 for f in feats] for feats, run in runs])
    b = np.array([run["wall_s"] for _, run in runs])
    w = 1.0 / np.maximum(b, 1e-3)
    x, _ = nnls(A * w[:, None], b * w)
    return float(x[0]), tuple(float(v) for v in x[1:])


def measure(scenes, budget: int) -> list[dict]:
    out = []
    for name, path, sets in scenes:
        try:
            cfg = load_design(str(path), sets).design
            design = compute_design(cfg)
        except GearcliError as exc:
            print(f"{name}: skipped ({exc})", flush=True)
            continue
        spec = spec_from_design(cfg, design)
        c = choose_method(spec, cfg.simulation.duration_s, "auto", cfg.simulation.rtol)
        row = {"scene": name, "predicted": list(c.predicted_evals), "features": list(c.size.features())}
        for m in METHODS:
            row[f"{m}/compiled"] = one(cfg, design, m, "compiled", cost.CAP)
            row[f"{m}/python"] = one(cfg, design, m, "python", budget)
        out.append(row)
        print(f"{name:48s} " + "  ".join(f"{m} {row[f'{m}/compiled']['nfev'] if row[f'{m}/compiled'] else '-':>8}"
                                         for m in METHODS), flush=True)
    return out


def judge(rows: list[dict], title: str) -> None:
    """Per scene: measured over predicted evaluations and price per evaluation, each method and engine."""
    print(f"\n{title}: measured / predicted (evaluations; price per evaluation on compiled and on scipy)")
    print("| scene | DOP853 nfev | Radau nfev | DOP853 price c | Radau price c | DOP853 price py | Radau price py |")
    print("|---|---|---|---|---|---|---|")
    nf: list[float] = []
    pr: list[float] = []
    for r in rows:
        cells = []
        for k, m in enumerate(METHODS):
            run = r.get(f"{m}/compiled") or r.get(f"{m}/python")
            ratio = run["nfev"] / r["predicted"][k] if run and r["predicted"][k] > 0 else None
            cells.append("-" if ratio is None else f"{ratio:.2f}")
            if ratio is not None:
                nf.append(ratio)
        for eng in ("compiled", "python"):
            for m in METHODS:
                run = r.get(f"{m}/{eng}")
                if not run or run["nfev"] < 2000 or run["wall_s"] <= 0:
                    cells.append("-")
                    continue
                size = cost.ModelSize(*[int(v) for v in r["features"][1:6]], bool(r["features"][6]))
                predicted = cost.predicted_wall_s(eng, m, run["nfev"], cost.RUN_FIXED_S.get(eng, 0.0), size)
                ratio = run["wall_s"] / predicted
                pr.append(ratio)
                cells.append(f"{ratio:.2f}")
        print(f"| {r['scene']} | " + " | ".join(cells) + " |")
    if nf:
        q = np.abs(np.log(nf))
        print(f"evaluations: median |error| x{np.exp(np.median(q)):.2f}, worst x{np.exp(q.max()):.2f} "
              f"({len(nf)} runs)")
    if pr:
        q = np.abs(np.log(pr))
        print(f"wall time at the measured evaluations: median |error| x{np.exp(np.median(q)):.2f}, worst "
              f"x{np.exp(q.max()):.2f} ({len(pr)} runs)")


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--only", nargs="*")
    ap.add_argument("--python-budget", type=int, default=300_000)
    ap.add_argument("--json")
    ap.add_argument("--load", help="a --json file of an earlier run: fit and judge it without running")
    ap.add_argument("--set", dest="which", default="all", choices=("fit", "held-out", "all"))
    args = ap.parse_args()
    engine.load()
    for m in METHODS:  # each method's entry loaded once before any run is timed (the first scene paid ~40 ms)
        engine.entry(m)
    sets = scene_sets()
    if args.load:
        data = json.loads(Path(args.load).read_text())
    else:
        data = {}
        for which in ("fit", "held-out"):
            if args.which in (which, "all"):
                chosen = [s for s in sets[which] if not args.only or any(o in s[0] for o in args.only)]
                data[which] = measure(chosen, args.python_budget)
                if args.json:
                    Path(args.json).write_text(json.dumps(data, indent=1))
    if data.get("fit"):
        print("\nfitted on the fitting set (wall = fixed + nfev x price(size), price in us):")
        print("features: " + ", ".join(cost.FEATURES))
        for eng in ("compiled", "python"):
            fixed_by_method = []
            for m in METHODS:
                fixed, coef = fit_prices(data["fit"], f"{m}/{eng}")
                print(f"  {eng:8s} {m:6s} fixed {fixed * 1e3:.3g} ms  price " + ", ".join(f"{v:.3g}" for v in coef))
                cost.PRICE_US[eng][m] = coef  # judged below with the fitted prices
                fixed_by_method.append(fixed)
            cost.RUN_FIXED_S[eng] = float(np.mean(fixed_by_method))
        judge(data["fit"], "fitting set")
    if data.get("held-out"):
        judge(data["held-out"], "held-out set")


if __name__ == "__main__":
    main()
