"""The compiled engine against scipy, every ratio measured side by side in one run.

    python benchmarks/bench_engine.py [--repeat 5] [--sweep-points 1000] [--no-report] [--json] [--engine-only]

(a) Seed integration (configs/concrete_mixer.toml, DOP853 at the file's rtol 1e-6): compiled kernel vs scipy's
    DOP853 around the generated right-hand side, median wall of --repeat, nfev of each; the compiled run's
    window-mean F_t error against a DOP853 reference at rtol 1e-12 (target: ratio <= 0.05, error <= 1e-5).
(b) The floor: bare `python -c "import click, pydantic, rich, numpy, scipy.integrate"` (median of --repeat).
(c) One-shot `gearcli simulate configs/concrete_mixer.toml --format json` (engine = auto), median of --repeat
    runs interleaved with the floor's, against the floor (the former one-shot target of 1.3x is withdrawn);
    beside it the same on the Python engine and as `python -m gearcli` (runpy's way in: ~0.03 s more). The command is the console script installed next to
    this interpreter (what users run), else `python -m gearcli`.
(d) Full `gearcli report configs/concrete_mixer.toml` (engine = auto) against the floor (target <= 3x).
(e) A seed speed sweep of --sweep-points points (engine = auto, all cores) against the floor (target <= 15x).
(f) The physical limit: the seed run's evaluations x the cost of one compiled evaluation (10^6 evaluations in a
    compiled loop), beside the measured compiled integration.
    Beside it the DOP853 kernel called directly (no worker thread, no packing), median of --repeat.
(g) The kernel's load per process: a fresh interpreter (numpy and scipy imported first, as a run has them) loads
    the cached kernel as a run does (numba import + the kernel module, then the DOP853 entry), median of --repeat;
    the compiled kernel must be built (`gearcli engine build`).
--engine-only: (a), (f) and (g) only.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

import numpy as np  # noqa: E402

SEED = ROOT / "configs" / "concrete_mixer.toml"
FLOOR = "import click, pydantic, rich, numpy, scipy.integrate"


def wall(cmd: list[str], repeat: int) -> float:
    return interleaved({"cmd": cmd}, repeat)["cmd"]


def interleaved(cmds: dict[str, list[str]], repeat: int, env_extra: dict[str, dict[str, str]] | None = None) -> dict:
    """Median wall time of each command, the commands run in turn ``repeat`` times (noise hits them alike)."""
    times: dict[str, list[float]] = {name: [] for name in cmds}
    for _ in range(repeat):
        for name, cmd in cmds.items():
            env = dict(os.environ, PYTHONPATH=str(ROOT), **(env_extra or {}).get(name, {}))
            t0 = time.perf_counter()
            subprocess.run(cmd, cwd=ROOT, env=env, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            times[name].append(time.perf_counter() - t0)
    return {name: statistics.median(ts) for name, ts in times.items()}


def gearcli_command() -> list[str]:
    """The console script users run (installed next to this interpreter), else ``python -m gearcli``."""
    script = Path(sys.executable).with_name("gearcli")
    return [str(script)] if script.exists() else [sys.executable, "-m", "gearcli"]


def seed_model():
    from gearcli.config import load_design
    from gearcli.design import compute_design
    from gearcli.scene import build_model

    cfg = load_design(str(SEED), []).design
    design = compute_design(cfg)
    return cfg, design, build_model(cfg, design)


def integration(repeat: int) -> dict:
    from gearcli import engine
    from gearcli.simulate import run_simulation
    from gearcli.simulate.solver import integrate

    cfg, design, model = seed_model()
    t_eval = np.linspace(0.0, cfg.simulation.duration_s, cfg.simulation.steps + 1)
    rtol = cfg.simulation.rtol
    loaded = engine.load()
    engine.entry("DOP853")
    py = [integrate(model, t_eval, "DOP853", rtol) for _ in range(repeat)]
    cc = [integrate(model, t_eval, "DOP853", rtol, engine="compiled") for _ in range(repeat)]
    py_s = statistics.median(r.wall_s for r in py)
    cc_s = statistics.median(r.wall_s for r in cc)

    cfg_c = cfg.model_copy(update={"simulation": cfg.simulation.model_copy(update={"engine": "compiled"})})
    run = run_simulation(cfg_c, design, method="DOP853", rtol=rtol, want_series=False)
    ref = run_simulation(cfg_c, design, method="DOP853", rtol=1e-12, want_series=False)
    err = max(abs(a.tangential_N.mean - b.tangential_N.mean) / abs(b.tangential_N.mean)
              for a, b in zip(run.stages, ref.stages, strict=True))
    y = model.initial_state()
    packed = engine.pack(model.arrays)
    n_eval = 1_000_000
    loaded.kernel.evaluate_many(packed, 0.3, y, np.int64(10))
    t0 = time.perf_counter()
    loaded.kernel.evaluate_many(packed, 0.3, y, np.int64(n_eval))
    per_eval = (time.perf_counter() - t0) / n_eval
    kernel_s = kernel_call_s(model, t_eval, rtol, repeat)
    return {"python_s": py_s, "compiled_s": cc_s, "ratio": cc_s / py_s, "nfev_python": py[0].nfev,
            "kernel_call_s": kernel_s, "kernel_ratio": kernel_s / py_s,
            "nfev_compiled": cc[0].nfev, "steps": cc[0].steps, "mean_force_error": err,
            "compiled_eval_s": per_eval, "physical_limit_s": cc[0].nfev * per_eval,
            "python_eval_s": py_s / py[0].nfev}


def kernel_call_s(model, t_eval: np.ndarray, rtol: float, repeat: int) -> float:
    """Median wall of the DOP853 kernel called directly (the run's arguments, no worker thread, no packing): what
    ``integrate`` adds around it (its worker thread for signals and progress, packing, the energy watch's setup) is
    the difference, and on a loaded machine the thread's scheduling is most of the spread."""
    from gearcli import engine
    from gearcli.simulate.solver import breakpoints

    kernel, _ = engine.entry("DOP853")
    n = model.n_states
    args = (engine.pack(model.arrays), model.initial_state(), t_eval, np.array(breakpoints(model, float(t_eval[-1]))),
            np.full(n, rtol), np.array(np.broadcast_to(model.atol(rtol), (n,)), dtype=float), np.int64(10**9),
            np.int64(0), np.zeros(5), np.empty(0))
    walls = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        kernel(*args)
        walls.append(time.perf_counter() - t0)
    return statistics.median(walls)


LOAD_PROBE = """
import time
import numpy, scipy.integrate
t0 = time.perf_counter()
import numba
t1 = time.perf_counter()
from gearcli import engine
engine.load(quiet=True)
t2 = time.perf_counter()
engine.entry("DOP853")
t3 = time.perf_counter()
print(t1 - t0, t2 - t1, t3 - t2)
"""


def load_per_process(repeat: int) -> dict:
    """Median over fresh interpreters of (numba import, kernel module, DOP853 entry) and their sum."""
    runs = []
    for _ in range(repeat):
        got = subprocess.run([sys.executable, "-c", LOAD_PROBE], cwd=ROOT, env=dict(os.environ, PYTHONPATH=str(ROOT)),
                             check=True, capture_output=True, text=True).stdout.split()
        runs.append([float(x) for x in got])
    cols = list(zip(*runs, strict=True))
    return {"numba_import_s": statistics.median(cols[0]), "kernel_module_s": statistics.median(cols[1]),
            "entry_s": statistics.median(cols[2]), "load_s": statistics.median(sum(r) for r in runs)}


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--sweep-points", type=int, default=1000)
    ap.add_argument("--no-report", action="store_true")
    ap.add_argument("--json", action="store_true")
    ap.add_argument("--engine-only", action="store_true", help="the integration ratio and the load per process only")
    args = ap.parse_args()
    py = sys.executable
    out: dict = {"load": load_per_process(args.repeat), "integration": integration(args.repeat)}
    if args.engine_only:
        _print_engine(out, args.json)
        return
    g = gearcli_command()
    one_shot = [*g, "simulate", str(SEED), "--format", "json"]
    shots = interleaved({"floor_s": [py, "-c", FLOOR], "simulate_s": one_shot,
                         "simulate_python_s": [*one_shot, "--set", "simulation.engine=python"],
                         "simulate_module_s": [py, "-m", "gearcli", *one_shot[len(g):]]}, args.repeat, {})
    out.update(shots)
    out["command"] = " ".join(Path(c).name if i == 0 else c for i, c in enumerate(g))
    floor = out["floor_s"]
    if not args.no_report:
        out["report_s"] = wall([*g, "report", str(SEED)], 1)
        out["report_python_s"] = wall([*g, "report", str(SEED), "--set", "simulation.engine=python"], 1)
    if args.sweep_points:
        with tempfile.TemporaryDirectory() as tmp:
            n = args.sweep_points
            for name, extra in (("sweep_s", []), ("sweep_python_s", ["--set", "simulation.engine=python"])):
                target = Path(tmp) / f"{name}.csv"
                out[name] = wall([*g, "sweep", str(SEED), "--vary",
                                  f"input.speed_deg_s=1800:5400:{n}", "-o", str(target), *extra], 1)
                target.unlink()
    if args.json:
        print(json.dumps(out, indent=2))
        return
    i = out["integration"]
    rows = [
        ("seed integration, compiled vs scipy DOP853", f"{i['compiled_s'] * 1e3:.2f} ms vs {i['python_s'] * 1e3:.1f} ms",
         f"{i['ratio']:.3f}x", "<= 0.05x"),
        ("  the kernel called alone (no worker thread)", f"{i['kernel_call_s'] * 1e3:.2f} ms", f"{i['kernel_ratio']:.3f}x",
         ""),
        ("  nfev (compiled / scipy), accepted steps", f"{i['nfev_compiled']} / {i['nfev_python']}, {i['steps']}", "", "equal"),
        ("  mean F_t error vs rtol 1e-12", f"{i['mean_force_error']:.1e}", "", "<= 1e-5"),
        ("  physical limit: nfev x one compiled evaluation", f"{i['physical_limit_s'] * 1e3:.2f} ms "
         f"({i['compiled_eval_s'] * 1e9:.0f} ns/eval; scipy {i['python_eval_s'] * 1e6:.1f} us/eval)", "", ""),
        ("  kernel load per process (fresh interpreter)", f"{out['load']['load_s']:.2f} s", "", ""),
        ("floor: import click+pydantic+rich+numpy+scipy.integrate", f"{floor:.2f} s", "1x", ""),
        ("one-shot gearcli simulate (auto)", f"{out['simulate_s']:.2f} s", f"{out['simulate_s'] / floor:.2f}x", ""),
        ("one-shot gearcli simulate (python)", f"{out['simulate_python_s']:.2f} s",
         f"{out['simulate_python_s'] / floor:.2f}x", ""),
        ("  the same as python -m gearcli", f"{out['simulate_module_s']:.2f} s",
         f"{out['simulate_module_s'] / floor:.2f}x", ""),
    ]
    if "report_s" in out:
        rows += [("gearcli report (auto)", f"{out['report_s']:.2f} s", f"{out['report_s'] / floor:.1f}x", "<= 3x"),
                 ("gearcli report (python)", f"{out['report_python_s']:.2f} s",
                  f"{out['report_python_s'] / floor:.1f}x", "")]
    if "sweep_s" in out:
        rows += [(f"{args.sweep_points}-point speed sweep (auto)", f"{out['sweep_s']:.1f} s",
                  f"{out['sweep_s'] / floor:.1f}x", "<= 15x"),
                 (f"{args.sweep_points}-point speed sweep (python)", f"{out['sweep_python_s']:.1f} s",
                  f"{out['sweep_python_s'] / floor:.1f}x", "")]
    width = max(len(r[0]) for r in rows)
    print(f"command: {out['command']} (medians of {args.repeat} interleaved runs)")
    print(f"{'measure':{width}}  {'figure':>44}  {'ratio':>8}  target")
    for name, fig, ratio, target in rows:
        print(f"{name:{width}}  {fig:>44}  {ratio:>8}  {target}")


def _print_engine(out: dict, as_json: bool) -> None:
    if as_json:
        print(json.dumps(out, indent=2))
        return
    i, ld = out["integration"], out["load"]
    print(f"seed integration, compiled vs scipy DOP853 (same rtol): {i['compiled_s'] * 1e3:.2f} ms vs "
          f"{i['python_s'] * 1e3:.1f} ms = {i['ratio']:.3f}x (target <= 0.05x)")
    print(f"  the kernel called alone (no worker thread, no packing): {i['kernel_call_s'] * 1e3:.2f} ms = "
          f"{i['kernel_ratio']:.3f}x scipy")
    print(f"  nfev compiled / scipy: {i['nfev_compiled']} / {i['nfev_python']}; mean F_t error vs rtol 1e-12: "
          f"{i['mean_force_error']:.1e} (target <= 1e-5)")
    print(f"  physical limit: {i['physical_limit_s'] * 1e3:.2f} ms ({i['compiled_eval_s'] * 1e9:.0f} ns per evaluation)")
    print(f"kernel load per process: {ld['load_s']:.2f} s (numba import {ld['numba_import_s']:.2f} s, kernel module "
          f"{ld['kernel_module_s']:.2f} s, DOP853 entry {ld['entry_s']:.2f} s)")


if __name__ == "__main__":
    main()
