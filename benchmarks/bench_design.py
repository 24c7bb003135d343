"""Wall time of `gearcli design` against the bare import of its runtime libraries, side by side.

    python benchmarks/bench_design.py [--repeat 15] [--json]

The command is the console script installed next to this interpreter (what users run; ``python -m
gearcli`` adds runpy's way in), else ``python -m gearcli``. Both commands run as fresh interpreters, interleaved (baseline, design, baseline, design, ...), so
machine noise hits both alike; the figure of merit is the ratio of the medians. Target (issue 2):
ratio <= 1.5.

    python benchmarks/bench_design.py --rating [--repeat 15] [--json]

The strength rating's cost (issue 22): `gearcli design` of the industrial two-stage reducer without and with
its ``[rating]`` (configs/industrial_two_stage.toml and ..._rated.toml, the same stages), interleaved; the
figure of merit is the ratio rated/unrated of the medians (target: no perceptible difference, ≤ 1.05).
Where PYTHONDONTWRITEBYTECODE is set, run ``python -m compileall gearcli`` first, or the new modules are
compiled from source on every run (an installed package ships them compiled).
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SEED = ROOT / "configs" / "concrete_mixer.toml"
BASELINE = [sys.executable, "-c", "import click, pydantic, rich.console, numpy"]
_SCRIPT = Path(sys.executable).with_name("gearcli")  # the console script users run, else python -m gearcli
DESIGN = [*([str(_SCRIPT)] if _SCRIPT.exists() else [sys.executable, "-m", "gearcli"]), "design", str(SEED),
          "--format", "json"]


def wall(cmd: list[str]) -> float:
    t0 = time.perf_counter()
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return time.perf_counter() - t0


def _command(config: Path) -> list[str]:
    return [*DESIGN[:-4], "design", str(config), "--format", "json"]


def rating_cost(repeat: int) -> dict:
    """Medians of `gearcli design` on the same reducer without and with [rating], interleaved."""
    plain = _command(ROOT / "configs" / "industrial_two_stage.toml")
    rated = _command(ROOT / "configs" / "industrial_two_stage_rated.toml")
    wall(plain), wall(rated)
    a, b = [], []
    for _ in range(repeat):
        a.append(wall(plain))
        b.append(wall(rated))
    return {"unrated_median_s": statistics.median(a), "rated_median_s": statistics.median(b),
            "ratio": statistics.median(b) / statistics.median(a), "repeat": repeat, "target_ratio": 1.05}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--repeat", type=int, default=15)
    ap.add_argument("--json", action="store_true")
    ap.add_argument("--rating", action="store_true", help="time the strength rating: rated vs unrated design")
    args = ap.parse_args()
    if args.rating:
        out = rating_cost(args.repeat)
        if args.json:
            print(json.dumps(out, indent=2))
        else:
            print(f"design industrial_two_stage.toml        median {out['unrated_median_s']*1e3:7.1f} ms")
            print(f"design industrial_two_stage_rated.toml  median {out['rated_median_s']*1e3:7.1f} ms")
            print(f"ratio rated/unrated = {out['ratio']:.3f}  (target <= 1.05, {args.repeat} interleaved runs each)")
        return
    wall(BASELINE), wall(DESIGN)  # warm the file cache
    base, design = [], []
    for _ in range(args.repeat):
        base.append(wall(BASELINE))
        design.append(wall(DESIGN))
    out = {
        "baseline_median_s": statistics.median(base),
        "design_median_s": statistics.median(design),
        "ratio": statistics.median(design) / statistics.median(base),
        "repeat": args.repeat,
        "target_ratio": 1.5,
    }
    if args.json:
        print(json.dumps(out, indent=2))
    else:
        print(f"baseline  python -c 'import click, pydantic, rich.console, numpy'  median {out['baseline_median_s']*1e3:7.1f} ms")
        print(f"gearcli design configs/concrete_mixer.toml --format json          median {out['design_median_s']*1e3:7.1f} ms")
        print(f"ratio design/baseline = {out['ratio']:.2f}  (target <= 1.5, {args.repeat} interleaved runs each)")


if __name__ == "__main__":
    main()
