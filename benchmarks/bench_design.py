"""Wall time of `gearcli design` against the bare import of its runtime libraries, side by side.

    python benchmarks/bench_design.py [--repeat 15] [--json]

The command is the console script installed next to this interpreter (what users run; ``python -m
gearcli`` adds runpy's way in), else ``python -m gearcli``. Both commands run as fresh interpreters, interleaved (baseline, design, baseline, design, ...), so
machine noise hits both alike; the figure of merit is the ratio of the medians. Target (issue 2):
ratio <= 1.5.
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


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--repeat", type=int, default=15)
    ap.add_argument("--json", action="store_true")
    args = ap.parse_args()
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
