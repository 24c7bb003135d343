"""Cost of a transmission-error excited run: 300 mesh periods of the single-mesh spur oscillator.

    python benchmarks/bench_excitation.py [--repeat 5] [--rtol 1e-6] [--json]

configs/spur_oscillator_te.toml (one spur mesh, exponent 1, 0.1 mm backlash, zeta = 0.05, a 5 um TE)
at input speeds below, at and above the mesh resonance (f_n = 1 kHz: 1500, 2400, 2800 rpm; the mesh
frequency is 25 n / 60), each for exactly 300 mesh periods: integration wall time (median of --repeat),
nfev and nfev per mesh period, the method "auto" picks, the energy residual, and the mean and the range
of the mesh's penetration over the window (the dynamic response: no impact at 1500 rpm, impacts at 2400).
"""

from __future__ import annotations

import argparse
import json
import statistics
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from gearcli.config import load_design  # noqa: E402
from gearcli.design import compute_design  # noqa: E402
from gearcli.simulate import run_simulation  # noqa: E402

SCENE = ROOT / "configs" / "spur_oscillator_te.toml"
PERIODS = 300
SPEEDS_RPM = (1500.0, 2400.0, 2800.0)


def one(rpm: float, rtol: float, repeat: int) -> dict:
    z = 25  # pinion teeth of the scene
    duration = PERIODS * 60.0 / (z * rpm)
    sets = [f"input.speed_rpm={rpm}", f"simulation.duration_s={duration!r}", f"simulation.steps={PERIODS * 20}",
            f"simulation.rtol={rtol}"]
    cfg = load_design(str(SCENE), sets).design
    design = compute_design(cfg)
    walls, sim = [], None
    for _ in range(repeat):
        sim = run_simulation(cfg, design, want_series=False)
        walls.append(sim.solver.wall_s)
    assert sim is not None
    pen = sim.stages[0].penetration_mm
    return {"speed_rpm": rpm, "mesh_Hz": z * rpm / 60.0, "periods": PERIODS, "rtol": rtol,
            "method": sim.solver.method, "wall_s": statistics.median(walls), "nfev": sim.solver.nfev,
            "nfev_per_period": sim.solver.nfev / PERIODS, "steps": sim.solver.steps,
            "energy_residual": sim.solver.energy_residual, "penetration_mean_um": 1e3 * pen.mean,
            "penetration_range_um": [1e3 * pen.min, 1e3 * pen.max]}


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--rtol", type=float, default=1e-6)
    ap.add_argument("--json", action="store_true")
    args = ap.parse_args()
    rows = [one(rpm, args.rtol, args.repeat) for rpm in SPEEDS_RPM]
    if args.json:
        print(json.dumps(rows, indent=2))
        return
    print(f"{'rpm':>6} {'mesh Hz':>8} {'method':>7} {'wall s':>8} {'nfev':>7} {'nfev/period':>11} "
          f"{'energy res':>10}  penetration um (mean, min..max)")
    for r in rows:
        lo, hi = r["penetration_range_um"]
        print(f"{r['speed_rpm']:6.0f} {r['mesh_Hz']:8.1f} {r['method']:>7} {r['wall_s']:8.3f} {r['nfev']:7d} "
              f"{r['nfev_per_period']:11.1f} {r['energy_residual']:10.2g}  {r['penetration_mean_um']:.3f}, "
              f"{lo:.3f}..{hi:.3f}")


if __name__ == "__main__":
    main()
