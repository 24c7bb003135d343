"""Numerical robustness: run the extreme-scene catalogue (configs/extreme/) and print the README table.

    python benchmarks/robustness.py [--scene NAME ...] [--no-legend]

For every scene: the method ``method = "auto"`` picked, the function evaluations (and the ceiling the
test allows), the integration wall time, and each independent check with its value, its tolerance and
pass/fail. The checks, tolerances and their reasons live in tests/extreme/catalogue.py, shared with
tests/extreme/test_catalogue.py, so the table shows exactly what CI asserts. (The spec is a test oracle,
not product code, so it stays under tests/; this script loads it by path.) Exit status 1 if a check fails.
"""

from __future__ import annotations

import argparse
import platform
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT), str(ROOT / "tests" / "extreme")]

import catalogue  # noqa: E402  (tests/extreme/catalogue.py)

LABELS = {
    "ratio": "ratio err", "force": "Newton F_t err", "static_force": "F_t vs static", "penetration": "pen. vs h0",
    "conservation": "energy (channels)", "dissipation": "dissipation", "energy_residual": "energy residual",
    "rigid": "rigid-body energy", "flanks": "flanks", "quasi_static": "peak vs rigid", "axial": "F_a = F_t tan β",
    "input_speed": "input speed", "warning": "warned", "damping_loss": "damping loss", "ringing": "std F_t / F",
}
LEGEND = """\
- ratio err: |mean w_in / mean w_out over the steady window / product of z_gear/z_pinion - 1|
- Newton F_t err: window-mean F_t of every stage against the static force from the load and the pitch radii plus
  the momentum change of the driven shafts over the window (largest relative error over the stages)
- F_t vs static: window-mean F_t against the static force alone (scenes that settle)
- pen. vs h0: window-mean penetration against h0 = (F_n / K)^(1/e), K = 4/3 sqrt(R) E* or the file's number
- energy (channels): |W_in - W_load - dKE - dPE| / W_in from the CSV columns alone (undamped scenes)
- dissipation: energy the channels say was created (damping may only remove energy); 0 when none
- energy residual: the model's own balance (work quadratures)
- rigid-body energy: dKE and W_load against the rigid train's (stiff limit)
- flanks: stages whose penetration sign disagrees with the expected flank(s)
- peak vs rigid: run peak |F_t| against the rigid train's peak (quasi-static run-up)
- F_a = F_t tan β: max |F_a - F_t tan β| / max |F_t|
- input speed: mean speed of a free input shaft against the nominal one (balanced torque drive)
- warned: stages missing an expected warning; damping loss: loss / input work; std F_t / F: ringing left"""


def describe(outcome) -> str:
    label = LABELS.get(outcome.kind, outcome.kind)
    if outcome.kind == "flanks":  # text: "<expected> flanks over the <where>: ..."
        return f"{outcome.text.split(':')[0]}: {int(outcome.value)} stages off"
    if outcome.kind == "warning":
        return f"{label}: {int(outcome.value)} stages missing"
    return f"{label} {outcome.value:.1e} (≤ {outcome.tol:.0e})"


def table(runs) -> str:
    lines = ["| scene | auto → method | nfev (ceiling) | wall s | independent checks: value (tolerance) | pass |",
             "|---|---|---|---|---|---|"]
    for run in runs:
        sv = run.result.solver
        checks = "; ".join(describe(o) for o in run.outcomes[4:])
        lines.append(f"| {run.scene.name} | {sv.method} | {sv.nfev:,} ({run.scene.nfev_ceiling:,}) | "
                     f"{run.wall_s:.2f} | {checks} | {'pass' if run.ok else 'FAIL'} |")
    return "\n".join(lines)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scene", action="append", help="run only this scene (repeatable)")
    ap.add_argument("--no-legend", action="store_true")
    args = ap.parse_args(argv)
    scenes = [s for s in catalogue.SCENES if not args.scene or s.name in args.scene]
    runs = []
    for s in scenes:
        print(f"running {s.name} ...", file=sys.stderr, flush=True)
        runs.append(catalogue.run_scene(s))
    print(table(runs))
    total = sum(r.wall_s for r in runs)
    print(f"\n{sum(r.ok for r in runs)}/{len(runs)} scenes pass; integration {total:.1f} s in all "
          f"(Python {platform.python_version()}, {platform.machine()}). Common checks on every scene: the run "
          "finishes with the method auto is expected to pick, every channel is finite, nfev ≤ ceiling.")
    if not args.no_legend:
        print("\n" + LEGEND)
    failed = [f"{r.scene.name}: {o.kind}: {o.text}" for r in runs for o in r.outcomes if not o.ok]
    for line in failed:
        print(f"FAIL {line}", file=sys.stderr)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
