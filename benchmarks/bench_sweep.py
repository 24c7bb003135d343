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
first), each part timed by patching the functions that do it (:func:`_parts`; a call's own time, less the
patched calls inside it): the integration (every integration of the point: its run, the settle test's longer
runs and the periodic search's shots, gearcli.simulate.settle), the check pass (on the points a sweep checks:
every gearcli.sweep.family.CHECK_EVERY-th), the design and model set-up (a continued point's model with the
previous point's phases carried), the run's set-up (a continued point's start state, the equations' arrays,
the method and engine choice, the steady-state search's own algebra such as the equilibrium's Newton, each
integration's preparation) and the post-processing (output sampling and energy balance, statistics with the
ringing fit and settle test, diagnostics and warnings, the simulated rating, and the untimed lines between the
parts); the parts sum to the point. Printed: post-processing / integration (issue 33's target <= 0.20) and
(run set-up + post-processing) / integration, both. The points run in this process's main thread, whose Python
SIGINT handler makes each compiled integration run in a worker thread (gearcli.simulate.solver's
_kernel_with_progress), as in `gearcli sweep --jobs 1`; a pool worker (--jobs 2 and up) ignores SIGINT and calls the
kernel directly. The thread's start and join count to the integration.

    python benchmarks/bench_sweep.py --points 1000 --loop 0 --no-dask     # the sweep against the floor only
    python benchmarks/bench_sweep.py --points 2 --loop 0 --no-dask --breakdown 200 --continued --detail

``--continued``: the breakdown's points continue one from the other as ``gearcli sweep`` runs a branch (its
integrations start near the next equilibrium: shorter than a cold point's); ``--detail``: the post-processing's
CPU function by function (each timed function's own time, the statistics' and output sampling's steps and the
facade's and the run's own lines timed too, each counted to the part it runs in: the parts' sums stay theirs, the
extra timers' own cost, ~1 us a call, with them).
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
# the BLAS thread counts the CLI sets for itself (gearcli.__main__.BLAS_THREADS), for the floor too (bench_cli.py)
ENV = {**os.environ, **{name: os.environ.get(name, "1") for name in ("OMP_NUM_THREADS", "MKL_NUM_THREADS",
                                                                     "OPENBLAS_NUM_THREADS")},
       "PYTHONPATH": str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", "")}
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


# The per-point breakdown's parts, each the functions whose own time (less the parts timed inside them) it counts.
# A function is patched wherever a gearcli module holds it (``from x import f`` copies included); what runs inside
# the check pass or the design counts to them whole. Post-processing is what is left of the point: its named
# sub-parts below, and the facade's and the run's own lines between the parts (``other``), so nothing is lost.
SETUP = "run set-up"
POST = ("output sampling", "statistics", "diagnostics", "rating", "other")


def _parts():
    """(module or class, attribute, part, absorbs) of every function the breakdown patches."""
    from gearcli import api
    from gearcli.model.assembly import Layout
    from gearcli.model.equations import TorsionalModel
    from gearcli.simulate import (
        course,
        equilibrium,
        estimate,
        guards,
        rigid_start,
        ringing,
        run,
        sampling,
        settle,
        shooting,
        solver,
        stats,
    )
    from gearcli.sweep import continuation

    # a continued point's (--continued) model carries the previous point's mesh phases (carry_phases: its model
    # spec) and its run starts from that point's state mapped onto it (continue_state: the run's initial state)
    whole = [(api, "design_case", "design and model"), (api, "spec_from_design", "design and model"),
             (api, "TorsionalModel", "design and model"), (estimate, "check_pass", "check pass"),
             (continuation, "carry_phases", "design and model"), (continuation, "continue_state", SETUP)]
    own = [(solver, "_integrate_compiled", "integration"), (solver, "_segment", "integration"),
           # set-up: what the run needs before (and around) its integrations: the memory and cost guard, the
           # equations' arrays, the method and engine choice and budget, the steady-state search's own algebra
           # (run-up start, equilibrium Newton, shooting), an integration's own preparation (energy watch,
           # tolerances, step ceiling)
           (api, "check_run_budget", SETUP), (Layout, "arrays", SETUP), (stats, "steady_window", SETUP),
           (run, "engine_options", SETUP), (run, "choose_method", SETUP), (run, "choose_engine", SETUP),
           (run, "_loadable", SETUP), (guards, "nfev_budget", SETUP), (guards, "require_feasible", SETUP),
           (run, "_at_rest", SETUP), (shooting, "priced_nfev", SETUP), (shooting, "integrate_shooting", SETUP),
           (course, "integrate_auto", SETUP), (solver, "integrate", SETUP), (run, "window_steady", SETUP),
           # post-processing: the samples' outputs and energy balance, the statistics, the diagnostics, the rating
           (run, "sample", "output sampling"), (equilibrium, "sampled", "output sampling"),
           (TorsionalModel, "energy", "output sampling"), (run, "_summarise", "statistics"),
           (run, "_design_diagnostics", "diagnostics"), (run, "resonance_warnings", "diagnostics"),
           (course, "pace_warnings", "diagnostics"), (stats, "model_warnings", "diagnostics"),
           (run, "_choice_warnings", "diagnostics"), (guards, "force_noise_warnings", "diagnostics"),
           (run, "steady_warnings", "diagnostics"), (estimate, "warnings", "diagnostics"),
           (rigid_start, "start_summary", "diagnostics"), (ringing, "ringing_warnings", "diagnostics"),
           (settle, "settled_steady", "diagnostics"), (stats, "contact_warnings", "diagnostics"),
           (sampling, "warnings", "diagnostics"), (sampling, "excitation_warnings", "diagnostics"),
           (sampling, "window_period_warnings", "diagnostics"),
           (sampling, "peak_warnings", "diagnostics"), (api, "with_simulated_rating", "rating")]
    return [(m, a, p, True) for m, a, p in whole] + [(m, a, p, False) for m, a, p in own]


def _detail():
    """(module or class, attribute) of the functions ``--detail`` times besides :func:`_parts`' (each counted to the
    part it runs in): the statistics' and the output sampling's own steps, the facade's and the run's own lines."""
    from gearcli import api
    from gearcli.model import outputs
    from gearcli.simulate import aliasing, estimate, planet_stats, run, settle, spent, stats

    return [(stats, "window_reductions"), (aliasing, "window_sampling"), (stats, "stages_dynamics"),
            (run, "_series"), (run, "mesh_stiffness"), (run, "simulated_static_tangential_N"),
            (estimate, "force_floors_N"), (stats, "window_mask"), (run, "_require_finite"), (run, "_atol_summary"),
            (planet_stats, "planets_of"), (outputs, "_all_series"), (outputs, "body_motion"),
            (run, "run_simulation"), (run, "simulate_model"), (api, "evaluate_point"), (settle, "periodic_state"),
            (spent, "totalled")]


def _patch(parts: dict[str, float], detail: dict[str, float] | None = None) -> list[tuple[object, str, object]]:
    """Patch every function of :func:`_parts` (see there); returns what to restore. Each call's own CPU time, less
    that of the patched calls inside it, goes to its part; an integration outside the check pass counts a run.
    ``detail``: each function's own time also goes there, keyed "part: function" (with :data:`DETAIL`'s functions
    patched too, each counted to the part of the function it runs in: the parts' sums are the same)."""
    stack: list[list] = []  # [part, start, time of the timed calls inside, absorbs, function]

    def timed(real, part: str | None, absorbs: bool, name: str):
        def wrapper(*a, **k):
            if any(e[3] for e in stack):
                return real(*a, **k)
            stack.append([part if part is not None else stack[-1][0] if stack else "other", time.process_time(), 0.0,
                          absorbs, name])
            try:
                return real(*a, **k)
            finally:
                p, t0, inner, _, fn = stack.pop()
                took = time.process_time() - t0
                parts[p] += took - inner
                parts["runs"] += p == "integration"
                if detail is not None:
                    detail[f"{p}: {fn}"] = detail.get(f"{p}: {fn}", 0.0) + took - inner
                if stack:
                    stack[-1][2] += took
        return wrapper

    saved = []
    patches = _parts() + ([(m, a, None, False) for m, a in _detail()] if detail is not None else [])
    mods = [m for name, m in list(sys.modules.items()) if name.startswith("gearcli") and m is not None]
    for owner, name, part, absorbs in patches:
        real = owner.__dict__[name]
        fake = timed(real, part, absorbs, name)
        for holder in [owner] if isinstance(owner, type) or isinstance(real, type) else mods:
            for attr, value in list(vars(holder).items()):
                if value is real:
                    saved.append((holder, attr, real))
                    setattr(holder, attr, fake)
    return saved


def breakdown(n: int, continued: bool = False, detail: dict[str, float] | None = None) -> dict[str, float]:
    """CPU seconds per point of a seed speed sweep in this process, by part (module text): the process's CPU
    time (the compiled kernel runs in a worker thread: counted), which other jobs on the machine do not inflate.
    "integration" is every integration of the point (the run, a settle test's longer runs, the periodic
    search's shots: :func:`gearcli.simulate.solver.integrate`'s engine part), "check pass" the check pass's
    whole cost (its integration included), "design and model" loading, designing and the model's set-up (the
    point's model parameters and its TorsionalModel), "run set-up" what the run needs before and around its
    integrations (the equations' arrays, built lazily on the run's first use; the method and engine choice; the
    steady-state search's own algebra: run-up start, the equilibrium's Newton, the shooting; an integration's
    preparation), and post-processing the rest (:data:`POST`: output sampling and energy balance, statistics,
    diagnostics, the simulated rating, and the lines between the parts, ``other``). The parts sum to the point.
    ``continued``: each point continued from the previous one's state, as ``gearcli sweep`` runs a branch
    (:mod:`gearcli.sweep.continuation`; the first cold); else every point cold from rest. ``detail``: filled with each
    timed function's own CPU seconds a point, keyed "part: function" (:func:`_patch`)."""
    from gearcli import api, engine
    from gearcli.sweep.family import CHECK_EVERY
    from gearcli.sweep.worker import Scene

    if engine.available():
        engine.load(quiet=True)
    scene = Scene(SEED.read_bytes(), str(SEED), (), 3)
    api.evaluate_point(scene, ("input.speed_rpm=600",))  # warm: generated code, caches, the lazy imports
    names = ["point", "integration", "check pass", "design and model", SETUP, *POST, "runs"]
    parts = dict.fromkeys(names, 0.0)
    own: dict[str, float] | None = {} if detail is not None else None
    saved = _patch(parts, own)
    engines = set()
    try:
        api.evaluate_point(scene, ("input.speed_rpm=600",))  # warm the patched calls
        parts.update(dict.fromkeys(parts, 0.0))
        if own is not None:
            own.clear()
        ev = None
        for i, v in enumerate(_speeds(n)):
            start = (ev.carried,) if continued and ev is not None and ev.carried is not None else ()
            t0 = time.process_time()
            ev = api.evaluate_point(scene, (f"input.speed_rpm={v!r}",), *start, check=i % CHECK_EVERY == 0)
            parts["point"] += time.process_time() - t0
            sv = ev.result.solver
            engines.add(f"{sv.method} ({sv.engine}), steady {ev.result.steady.mode if ev.result.steady else '-'}")
    finally:
        for holder, attr, real in reversed(saved):
            setattr(holder, attr, real)
    if detail is not None and own is not None:
        detail.update({k: v / n for k, v in own.items()})
    out = {k: v / n for k, v in parts.items()}
    timed = sum(out[k] for k in names[1:-1] if k != "other")
    out["other"] = out["point"] - timed  # the untimed lines: the facade's, the run's own between the parts
    out["post-processing"] = sum(out[k] for k in POST)
    out["engines"] = "; ".join(sorted(engines))  # type: ignore[assignment]
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--points", type=int, default=1000)
    ap.add_argument("--loop", type=int, default=20, help="shell-loop points actually run (then extrapolated)")
    ap.add_argument("--jobs", type=int, default=os.cpu_count() or 1)
    ap.add_argument("--no-dask", action="store_true")
    ap.add_argument("--breakdown", type=int, default=100, help="points of the in-process breakdown (0: none)")
    ap.add_argument("--continued", action="store_true",
                    help="the breakdown's points continued one from the other (as gearcli sweep), not cold")
    ap.add_argument("--detail", action="store_true", help="the breakdown's post-processing function by function")
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
        own: dict[str, float] | None = {} if args.detail else None
        b = breakdown(args.breakdown, args.continued, own)
        print(f"\nper point, in process, CPU ms ({args.breakdown} points, {'continued' if args.continued else 'cold'}; "
              f"{b.pop('engines')}; {b['runs']:.1f} integrations a point):")
        for k in ("point", "integration", "check pass", "design and model", SETUP, "post-processing"):
            print(f"  {k:<18} {1e3 * b[k]:8.2f}")
            if k == "post-processing":
                for sub in POST:
                    print(f"    {sub:<16} {1e3 * b[sub]:8.2f}")
        integ = b["integration"]
        print(f"  post-processing / integration: {b['post-processing'] / integ:.2f} (target <= 0.20)")
        print(f"  (run set-up + post-processing) / integration: {(b[SETUP] + b['post-processing']) / integ:.2f}")
        if own is not None:
            print("  post-processing by function (own CPU ms; 'other: f' is a function among the untimed lines):")
            for key, v in sorted(own.items(), key=lambda kv: -kv[1]):
                if key.split(":")[0] in POST:
                    print(f"    {key:<44} {1e3 * v:7.3f}")

if __name__ == "__main__":
    main()
