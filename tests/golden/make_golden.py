"""Record the simulate summary of every scene in configs/ and configs/extreme/ (the golden numbers).

    OPENBLAS_CORETYPE=Haswell PYTHONPATH=$PWD python tests/golden/make_golden.py [--only NAME ...]

(the OpenBLAS kernel tests/conftest.py pins for the test session: Newton's linear solves in a periodic run
round differently on other kernels, and the integer counters must match exactly.)

Each scene runs with the method and rtol its file gives (``run_simulation`` defaults) and its numbers
go to tests/golden/<dir>__<name>.json. ``test_golden.py`` re-runs the scenes and requires agreement to
the run's resolution (and, in the bitwise tier, to 1e-9 with the same steps).
Scenes that fail or take longer than ``SLOW_S`` are recorded with ``"slow": true`` (run only when
GEARCLI_GOLDEN_ALL=1) or left out with the reason in ``skipped.json``.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(ROOT))

SLOW_S = 3.0  # a scene slower than this runs only under GEARCLI_GOLDEN_ALL=1
SKIP_S = 20.0  # a scene slower than this is not recorded at all


def scene_files() -> list[Path]:
    return sorted((ROOT / "configs").glob("*.toml")) + sorted((ROOT / "configs" / "extreme").glob("*.toml"))


def golden_name(path: Path) -> str:
    return f"{path.parent.name}__{path.stem}"


def summary_numbers(path: Path) -> dict:
    """The numbers of the simulate JSON that a model refactoring must not change."""
    from gearcli.config import load_design
    from gearcli.design import compute_design
    from gearcli.simulate import run_simulation

    cfg = load_design(str(path), []).design
    # the scipy path, whatever auto would pick: the compiled engine's choice depends on what the process has
    # already compiled or loaded, and a compiled Radau (or Newton's variational periods) takes other steps
    cfg = cfg.model_copy(update={"simulation": cfg.simulation.model_copy(update={"engine": "python"})})
    sim = run_simulation(cfg, compute_design(cfg), want_series=False)
    stages = []
    for s in sim.stages:
        stages.append({q: [getattr(getattr(s, q), k) for k in ("mean", "min", "max", "std")]
                       for q in ("tangential_N", "radial_N", "axial_N", "penetration_mm")}
                      | {"peak_tangential_N": s.peak_tangential_N,
                         # the check pass's estimated error of mean, min, max, std of F_t (None without one)
                         "error_N": None if s.error_estimate is None else
                         [getattr(s.error_estimate.tangential_N, k) for k in ("mean", "min", "max", "std")]})
    return {"ratio": sim.ratio, "output_speed_deg_s": sim.output_speed_deg_s,
            "input_speed_deg_s": sim.input_speed_deg_s, "stages": stages,
            "method": sim.solver.method, "rtol": cfg.simulation.rtol, "nfev": sim.solver.nfev,
            "steps": sim.solver.steps,
            "energy_residual": sim.solver.energy_residual,
            "natural_frequencies_Hz": list(sim.natural_frequencies_Hz)}


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--only", nargs="*", default=None)
    args = ap.parse_args()
    skipped = {}
    for path in scene_files():
        name = golden_name(path)
        if args.only and name not in args.only and path.stem not in args.only:
            continue
        t0 = time.perf_counter()
        try:
            numbers = summary_numbers(path)
        except Exception as exc:  # noqa: BLE001 - a scene that fails today is recorded as skipped
            skipped[name] = f"fails today: {type(exc).__name__}: {exc}"
            print(f"{name}: SKIP ({skipped[name][:90]})")
            continue
        wall = time.perf_counter() - t0
        if wall > SKIP_S:
            skipped[name] = f"takes {wall:.0f} s"
            print(f"{name}: SKIP ({wall:.1f} s)")
            continue
        numbers["slow"] = wall > SLOW_S
        numbers["wall_s_when_recorded"] = round(wall, 2)
        (HERE / f"{name}.json").write_text(json.dumps(numbers, indent=1) + "\n")
        print(f"{name}: {wall:.2f} s {numbers['method']} nfev {numbers['nfev']}")
    if args.only is None:
        (HERE / "skipped.json").write_text(json.dumps(skipped, indent=1) + "\n")


if __name__ == "__main__":
    main()
