"""One-shot commands against the import floor and `report` against one `simulate`, pair by pair.

    python benchmarks/bench_cli.py [-n 7] [--only simulate,report-seed,...]

Each row runs its command A and its baseline B alternately (A B A B ..., fresh interpreters, a fresh output
file each run) and reports the median of the pairwise ratios A/B, of the wall clock and of the CPU time
(user + system of the child, which other jobs on a shared machine do not inflate), with the minimum of each
side. Rows (issue 33's targets):

- `design` on the seed against the floor (<= 1.5x);
- `simulate` on the seed against the floor (<= 1.6x), as `python -m gearcli` and (`simulate-script`) as the
  `gearcli` console script the README's commands run (the interpreter's own start differs between the two: `-m`
  runs the package through runpy, two frames deeper; docs/performance.md, "The one-shot `simulate`, session 17");
- `report` on the seed against the floor (<= 3x);
- `report` on the excited conveyor (configs/conveyor.toml) against one `simulate` of it (<= 10x).

The floor: `python -c "import click, pydantic, rich, numpy, scipy.integrate"`. Every command runs as
`python -m gearcli ...` with this checkout first on PYTHONPATH, and with the bytecode cache on
(PYTHONDONTWRITEBYTECODE is dropped from the children's environment). The CLI runs BLAS on one thread
(`gearcli.__main__.BLAS_THREADS`, as a Dask worker does: docs/sweeps.md), which spares it OpenBLAS's thread start;
every child here, the floor too, gets the same thread counts, so the floor pays no start the command is spared.
"""

from __future__ import annotations

import argparse
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
# without PYTHONDONTWRITEBYTECODE: the warm-up run writes this checkout's bytecode, as an installed package has it
# (with it, every run compiles gearcli's ~150 modules from source: ~0.25 s of CPU more per command)
ENV = {**{k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"},
       **{name: os.environ.get(name, "1") for name in ("OMP_NUM_THREADS", "MKL_NUM_THREADS", "OPENBLAS_NUM_THREADS")},
       "PYTHONPATH": str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", "")}
SEED = ROOT / "configs" / "concrete_mixer.toml"
CONVEYOR = ROOT / "configs" / "conveyor.toml"
FLOOR = [sys.executable, "-c", "import click, pydantic, rich, numpy, scipy.integrate"]


SCRIPT = Path(sys.executable).with_name("gearcli")  # the console script installed beside this interpreter


def gearcli(*args: str) -> list[str]:
    return [sys.executable, "-m", "gearcli", *args]


ROWS = {  # name: (A, B, target A/B)
    "design": (lambda d: gearcli("design", str(SEED), "-o", str(d / "d.json")), lambda d: FLOOR, 1.5),
    "simulate": (lambda d: gearcli("simulate", str(SEED), "-o", str(d / "s.json")), lambda d: FLOOR, 1.6),
    "simulate-script": (lambda d: [str(SCRIPT), "simulate", str(SEED), "-o", str(d / "s.json")], lambda d: FLOOR,
                        1.6),
    "report-seed": (lambda d: gearcli("report", str(SEED), "-o", str(d / "r.md")), lambda d: FLOOR, 3.0),
    "report-conveyor": (lambda d: gearcli("report", str(CONVEYOR), "-o", str(d / "rc.md")),
                        lambda d: gearcli("simulate", str(CONVEYOR), "-o", str(d / "sc.json")), 10.0),
}


def timed(cmd: list[str], cwd: Path) -> tuple[float, float]:
    """Wall and CPU seconds (the child's user + system) of one run."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    res = subprocess.run(cmd, cwd=cwd, env=ENV, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if res.returncode not in (0, 1):  # 1: the run finished with warnings
        raise SystemExit(f"{' '.join(cmd)} failed ({res.returncode}): {res.stderr[-800:]}")
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def pairs(name: str, n: int, tmp: Path) -> dict[str, float]:
    a_cmd, b_cmd, target = ROWS[name]
    timed(a_cmd(tmp), tmp)  # warm: the file cache, the compiled engine's cache, __pycache__
    a, b = [], []
    for _ in range(n):
        a.append(timed(a_cmd(tmp), tmp))
        b.append(timed(b_cmd(tmp), tmp))
    return {"wall": statistics.median(x[0] / y[0] for x, y in zip(a, b, strict=True)),
            "cpu": statistics.median(x[1] / y[1] for x, y in zip(a, b, strict=True)),
            "a_min": min(x[0] for x in a), "b_min": min(y[0] for y in b),
            "a_cpu_min": min(x[1] for x in a), "b_cpu_min": min(y[1] for y in b), "target": target}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("-n", type=int, default=7, help="pairs per row")
    ap.add_argument("--only", default=",".join(ROWS), help=f"comma-separated rows of: {', '.join(ROWS)}")
    args = ap.parse_args()
    print(f"load average {os.getloadavg()[0]:.1f} at the start; {args.n} pairs per row; medians of A/B")
    print(f"{'A against B':<18} {'wall A/B':>9} {'CPU A/B':>8} {'min A s':>8} {'min B s':>8} "
          f"{'CPU A s':>8} {'CPU B s':>8} {'target':>7}")
    with tempfile.TemporaryDirectory() as d:
        for name in args.only.split(","):
            if name == "simulate-script" and not SCRIPT.exists():
                print(f"{name:<18} (no console script at {SCRIPT})")
                continue
            r = pairs(name, args.n, Path(d))
            met = "met" if r["cpu"] <= r["target"] and r["wall"] <= r["target"] else "NOT met"
            print(f"{name:<18} {r['wall']:9.2f} {r['cpu']:8.2f} {r['a_min']:8.2f} {r['b_min']:8.2f} "
                  f"{r['a_cpu_min']:8.2f} {r['b_cpu_min']:8.2f} {r['target']:6.1f}x {met}", flush=True)
    print(f"load average {os.getloadavg()[0]:.1f} at the end")


if __name__ == "__main__":
    main()
