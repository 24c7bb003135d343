"""``method = "auto"`` against both of its methods on every scene (README "Accuracy", "auto").

    PYTHONPATH=$PWD python benchmarks/bench_auto.py [--only NAME ...] [--json FILE]

For every scene of configs/ and configs/extreme/ (and the seed at duration 10 s, the case of issue 10),
DOP853 and Radau run at the file's rtol (no error estimate, same samples; an evaluation budget of 3e6, a
run beyond it counts as "budget"), integration wall time (median of 3) and nfev/njev/nlu. "auto" runs
exactly the method it chooses (:func:`gearcli.simulate.choice.choose_method`), so its cost is that
method's; the ratio is auto's wall over the better method's (target: <= 1.3). Also the cost model's
inputs: microseconds per right-hand side, per Jacobian and per LU pair of the scene, measured here.
"""

from __future__ import annotations

import argparse
import json
import statistics
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "benchmarks"))

from gearcli.config import load_design  # noqa: E402
from gearcli.design import compute_design  # noqa: E402
from gearcli.errors import SimulationError  # noqa: E402
from gearcli.scene import spec_from_design  # noqa: E402
from gearcli.simulate import run_simulation  # noqa: E402
from gearcli.simulate.choice import choose_method, unit_costs  # noqa: E402

BUDGET = 3_000_000
REPEAT = 3


def excitation_scenes():
    """benchmarks/bench_excitation.py's scenes: the spur oscillator with a transmission error, 300 mesh periods
    below, at and above its mesh resonance."""
    from bench_excitation import PERIODS, SCENE, SPEEDS_RPM

    out = []
    for rpm in SPEEDS_RPM:
        duration = PERIODS * 60.0 / (25 * rpm)
        out.append((f"excitation/spur_te @ {rpm:g} rpm", SCENE,
                    [f"input.speed_rpm={rpm}", f"simulation.duration_s={duration!r}", f"simulation.steps={PERIODS * 20}"]))
    return out


def scenes():
    seed = ROOT / "configs" / "concrete_mixer.toml"
    out = [(f"{p.parent.name}/{p.stem}", p, []) for p in sorted((ROOT / "configs").glob("*.toml"))]
    out.append(("configs/concrete_mixer @ 10 s", seed, ["simulation.duration_s=10", "simulation.steps=40000"]))
    out += [(f"{p.parent.name}/{p.stem}", p, []) for p in sorted((ROOT / "configs" / "extreme").glob("*.toml"))]
    return out + excitation_scenes()


def timed(cfg, design, method: str) -> dict:
    walls = []
    for _ in range(REPEAT):
        try:
            sim = run_simulation(cfg, design, method=method, want_series=False, max_nfev=BUDGET, error_estimate=False)
        except SimulationError as exc:
            return {"failed": str(exc)[:80]}
        walls.append(sim.solver.wall_s)
        if sim.solver.wall_s > 5.0:  # one run of a slow case is enough
            break
    s = sim.solver
    return {"wall_s": statistics.median(walls), "nfev": s.nfev, "njev": s.njev, "nlu": s.nlu, "steps": s.steps}


def row(name: str, path: Path, overrides: list[str]) -> dict:
    cfg = load_design(str(path), overrides).design
    design = compute_design(cfg)
    spec = spec_from_design(cfg, design)
    choice = choose_method(spec, cfg.simulation.duration_s, "auto", cfg.simulation.rtol)
    d, r = timed(cfg, design, "DOP853"), timed(cfg, design, "Radau")
    walls = {m: x["wall_s"] for m, x in (("DOP853", d), ("Radau", r)) if "wall_s" in x}
    best = min(walls.values()) if walls else float("nan")
    auto = walls.get(choice.method, float("inf"))
    return {"scene": name, "indicator": choice.indicator, "vibration_rad": choice.vibration_rad,
            "predicted": list(choice.predicted_evals), "auto": choice.method, "reason": choice.reason,
            "DOP853": d, "Radau": r, "ratio": auto / best, "unit_costs_us": unit_costs(spec)}


def us_per_eval(x: dict) -> str:
    return f"{1e6 * x['wall_s'] / x['nfev']:.0f}" if "wall_s" in x else "–"


def cell(x: dict) -> str:
    return "budget/failed" if "wall_s" not in x else f"{x['wall_s']:.3f} s, {x['nfev']} fev"


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--only", nargs="*", default=None)
    ap.add_argument("--json", default=None)
    args = ap.parse_args()
    rows = []
    print("| scene | max\\|λ\\|·T | P [rad] | predicted DOP853 / Radau | DOP853 | Radau | µs/eval D / R "
          "| auto | auto / better |")
    print("|---|---|---|---|---|---|---|---|---|")
    for name, path, ov in scenes():
        if args.only and not any(o in name for o in args.only):
            continue
        r = row(name, path, ov)
        rows.append(r)
        print(f"| {name} | {r['indicator']:.3g} | {r['vibration_rad']:.3g} | {r['predicted'][0]:.3g} / "
              f"{r['predicted'][1]:.3g} | {cell(r['DOP853'])} | {cell(r['Radau'])} | {us_per_eval(r['DOP853'])} / "
              f"{us_per_eval(r['Radau'])} | {r['auto']} | {r['ratio']:.2f} |", flush=True)
    if args.json:
        Path(args.json).write_text(json.dumps(rows, indent=1) + "\n")


if __name__ == "__main__":
    main()
