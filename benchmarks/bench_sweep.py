"""Points per second of `gearcli sweep` on the seed speed sweep, against a shell loop, side by side.

    python benchmarks/bench_sweep.py [--points 1000] [--loop 20] [--jobs N]

The sweep: configs/concrete_mixer.toml, input speed 300 ... 1500 rpm in --points steps (independent
points, cold starts, the file's ramps). Measured in one run:
- the shell loop: `gearcli simulate FILE --set input.speed_rpm=V -o row.json` in a subprocess per point,
  --loop of them timed and extrapolated to --points (the way a sweep is done without this command);
- `gearcli sweep` with --jobs 1, with --jobs N (default: all cores), and on a Dask LocalCluster of N
  single-threaded worker processes (started here; its start-up is not counted, a cluster outlives a sweep).
Every sweep runs as `python -m gearcli sweep ... -o out.csv` in a subprocess, start-up included.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SEED = ROOT / "configs" / "concrete_mixer.toml"
ENV = {**os.environ, "PYTHONPATH": str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", "")}
os.environ["PYTHONPATH"] = ENV["PYTHONPATH"]  # the Dask workers started here import gearcli too
sys.path.insert(0, str(ROOT))


def _speeds(n: int) -> list[float]:
    return [300.0 + 1200.0 * i / max(1, n - 1) for i in range(n)]


def shell_loop(n: int, tmp: Path) -> float:
    """Seconds per point of one `gearcli simulate` subprocess per point."""
    t0 = time.perf_counter()
    for v in _speeds(n):
        subprocess.run([sys.executable, "-m", "gearcli", "simulate", str(SEED), "--set", f"input.speed_rpm={v!r}",
                        "-o", str(tmp / "row.json")], check=True, env=ENV, capture_output=True)
    return (time.perf_counter() - t0) / n


def sweep(n: int, tmp: Path, *extra: str) -> float:
    out = tmp / f"sweep{len(list(tmp.iterdir()))}.csv"
    t0 = time.perf_counter()
    res = subprocess.run([sys.executable, "-m", "gearcli", "sweep", str(SEED), "--vary", f"input.speed_rpm=300:1500:{n}",
                          "-o", str(out), *extra], env=ENV, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    if res.returncode != 0 or "0 failed" not in res.stderr:
        raise SystemExit(f"sweep {extra} failed: {res.stderr[-500:]}")
    return wall


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--points", type=int, default=1000)
    ap.add_argument("--loop", type=int, default=20, help="shell-loop points actually run (then extrapolated)")
    ap.add_argument("--jobs", type=int, default=os.cpu_count() or 1)
    args = ap.parse_args()
    n, jobs = args.points, args.jobs
    rows = []
    with tempfile.TemporaryDirectory() as d:
        tmp = Path(d)
        per = shell_loop(min(args.loop, n), tmp)
        rows.append((f"shell loop (gearcli simulate x {min(args.loop, n)}, extrapolated)", per * n))
        rows.append(("gearcli sweep --jobs 1", sweep(n, tmp, "--jobs", "1")))
        rows.append((f"gearcli sweep --jobs {jobs}", sweep(n, tmp, "--jobs", str(jobs))))
        try:
            from distributed import LocalCluster
        except ImportError:
            rows.append(("gearcli sweep --scheduler (dask not installed)", float("nan")))
        else:
            with LocalCluster(n_workers=jobs, threads_per_worker=1, processes=True, dashboard_address=None) as c:
                rows.append((f"gearcli sweep --scheduler (Dask LocalCluster, {jobs} workers)",
                             sweep(n, tmp, "--scheduler", c.scheduler_address)))
    base = rows[0][1]
    print(f"seed speed sweep, {n} points, {os.cpu_count()} cores (shared machine: absolute figures vary)")
    print(f"{'runner':<62} {'wall s':>9} {'points/s':>9} {'vs loop':>8}")
    for name, wall in rows:
        print(f"{name:<62} {wall:9.1f} {n / wall:9.2f} {base / wall:7.1f}x")


if __name__ == "__main__":
    main()
