"""Points per second of `gearcli sweep` on the seed speed sweep, against a shell loop, side by side.

    python benchmarks/bench_sweep.py [--points 1000] [--loop 20] [--jobs N]

The sweep: configs/concrete_mixer.toml, input speed 300 ... 1500 rpm in --points steps (independent
points, cold starts, the file's ramps). Measured in one run:
- the shell loop: `gearcli simulate FILE --set input.speed_rpm=V -o row.json` in a subprocess per point,
  --loop of them timed and extrapolated to --points (the way a sweep is done without this command);
- `gearcli sweep` with --jobs 1, with --jobs N (default: all cores), and on a Dask LocalCluster of N
  single-threaded worker processes (started here; its start-up is not counted, a cluster outlives a sweep).
Every sweep runs as `python -m gearcli sweep ... -o out.csv` in a subprocess, start-up included, and is set
against the import floor (`python -c "import click, pydantic, rich, numpy, scipy.integrate"`, the fastest of
three; target: the 1000-point sweep <= 15x the floor, aim 5x).

Then the per-point breakdown in CPU time (the process's: the compiled kernel's worker thread counted, other jobs
on the machine not), in this process (--breakdown points, the compiled engine where installed, the kernel loaded
first): the integration (every integration of the point: its run, the settle test's longer runs and the
periodic search's shots, gearcli.simulate.settle), the check pass (on the points a sweep checks: every
gearcli.sweep.family.CHECK_EVERY-th), the design and model set-up, and the post-processing (the rest:
statistics, ringing fit and settle test, error estimate's comparison, diagnostics), each per point and the
post-processing as a share of the integration (target <= 20 %).

    python benchmarks/bench_sweep.py --points 1000 --loop 0 --no-dask     # the sweep against the floor only
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


def floor_s(repeat: int = 3) -> float:
    cmd = [sys.executable, "-c", "import click, pydantic, rich, numpy, scipy.integrate"]
    best = float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter()
        subprocess.run(cmd, check=True, env=ENV)
        best = min(best, time.perf_counter() - t0)
    return best


def breakdown(n: int) -> dict[str, float]:
    """CPU seconds per point of a seed speed sweep in this process, by part (module text): the process's CPU
    time (the compiled kernel runs in a worker thread: counted), which other jobs on the machine do not inflate.
    "integration" is every integration of the point (the run, a settle test's longer runs, the periodic
    search's shots: :func:`gearcli.simulate.solver.integrate`'s engine part), "check pass" the check pass's
    whole cost (its integration included), "design and model" loading, designing and the model's set-up (the
    point's model parameters and its TorsionalModel; the equations' arrays, built lazily on the run's first use,
    count as post-processing)."""
    from gearcli import api, engine
    from gearcli.simulate import estimate, solver
    from gearcli.sweep.family import CHECK_EVERY
    from gearcli.sweep.worker import Scene

    if engine.available():
        engine.load(quiet=True)
    scene = Scene(SEED.read_bytes(), str(SEED), (), 3)
    parts = {"point": 0.0, "integration": 0.0, "check pass": 0.0, "design and model": 0.0, "runs": 0.0}
    inside = [False]

    def timed(real, part: str, runs: bool = False):
        def wrapper(*a, **k):
            if inside[0]:
                return real(*a, **k)
            inside[0] = True
            t0 = time.process_time()
            try:
                return real(*a, **k)
            finally:
                inside[0] = False
                parts[part] += time.process_time() - t0
                parts["runs"] += runs
        return wrapper

    patches = [(api, "design_case", "design and model", False), (api, "spec_from_design", "design and model", False),
               (api, "TorsionalModel", "design and model", False), (estimate, "check_pass", "check pass", False),
               (solver, "_integrate_compiled", "integration", True), (solver, "_segment", "integration", True)]
    saved = [(mod, name, getattr(mod, name)) for mod, name, _, _ in patches]
    for mod, name, part, runs in patches:
        setattr(mod, name, timed(getattr(mod, name), part, runs))
    engines = set()
    try:
        api.evaluate_point(scene, ("input.speed_rpm=600",))  # warm: generated code, caches
        parts.update({k: 0.0 for k in parts})
        for i, v in enumerate(_speeds(n)):
            t0 = time.process_time()
            ev = api.evaluate_point(scene, (f"input.speed_rpm={v!r}",), check=i % CHECK_EVERY == 0)
            parts["point"] += time.process_time() - t0
            sv = ev.result.solver
            engines.add(f"{sv.method} ({sv.engine}), steady {ev.result.steady.mode if ev.result.steady else '-'}")
    finally:
        for mod, name, real in saved:
            setattr(mod, name, real)
    out = {k: v / n for k, v in parts.items()}
    out["post-processing"] = out["point"] - out["integration"] - out["check pass"] - out["design and model"]
    out["engines"] = "; ".join(sorted(engines))  # type: ignore[assignment]
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--points", type=int, default=1000)
    ap.add_argument("--loop", type=int, default=20, help="shell-loop points actually run (then extrapolated)")
    ap.add_argument("--jobs", type=int, default=os.cpu_count() or 1)
    ap.add_argument("--no-dask", action="store_true")
    ap.add_argument("--breakdown", type=int, default=100, help="points of the in-process breakdown (0: none)")
    args = ap.parse_args()
    n, jobs = args.points, args.jobs
    rows = []
    floor = floor_s()
    with tempfile.TemporaryDirectory() as d:
        tmp = Path(d)
        if args.loop > 0:
            per = shell_loop(min(args.loop, n), tmp)
            rows.append((f"shell loop (gearcli simulate x {min(args.loop, n)}, extrapolated)", per * n))
        rows.append(("gearcli sweep --jobs 1", sweep(n, tmp, "--jobs", "1")))
        rows.append((f"gearcli sweep --jobs {jobs}", sweep(n, tmp, "--jobs", str(jobs))))
        try:
            if args.no_dask:
                raise ImportError
            from distributed import LocalCluster
        except ImportError:
            rows.append(("gearcli sweep --scheduler (not run)", float("nan")))
        else:
            with LocalCluster(n_workers=jobs, threads_per_worker=1, processes=True, dashboard_address=None) as c:
                rows.append((f"gearcli sweep --scheduler (Dask LocalCluster, {jobs} workers)",
                             sweep(n, tmp, "--scheduler", c.scheduler_address)))
    base = rows[0][1]
    print(f"seed speed sweep, {n} points, {os.cpu_count()} cores (shared machine: absolute figures vary); "
          f"import floor {floor:.2f} s")
    print(f"{'runner':<62} {'wall s':>9} {'points/s':>9} {'vs first':>8} {'/ floor':>8}")
    for name, wall in rows:
        print(f"{name:<62} {wall:9.1f} {n / wall:9.2f} {base / wall:7.1f}x {wall / floor:7.1f}x")
    if args.breakdown:
        b = breakdown(args.breakdown)
        print(f"\nper point, in process, CPU ms ({args.breakdown} points; {b.pop('engines')}; "
              f"{b['runs']:.1f} integrations a point):")
        for k in ("point", "integration", "check pass", "design and model", "post-processing"):
            print(f"  {k:<18} {1e3 * b[k]:8.2f}")
        print(f"  post-processing / integration: {b['post-processing'] / b['integration']:.2f} (target <= 0.20)")


if __name__ == "__main__":
    main()
