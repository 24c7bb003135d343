"""The benchmarks' scene sets: the fitting set of the cost model and the held-out set it never sees (issue 33).

The fitting set: configs/ and configs/extreme/ less the held-out files. The held-out set: files the cost
model's fit never sees (a drivetrain, a planetary gearbox, motor starts, excited, stiff and rattling scenes) and
variants of them a seeded generator draws (the ISO-calibrated Hertz mesh law with 5 % viscous damping that scenes
without [contact] get, a tighter or looser rtol, a longer or shorter run). benchmarks/bench_cost.py fits on the
first and judges on both; benchmarks/bench_auto.py reports the held-out set separately.
"""

from __future__ import annotations

import random
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def _duration(path: Path) -> tuple[float, int, float | None]:
    import tomllib

    sim = tomllib.loads(path.read_text(encoding="utf-8")).get("simulation", {})
    start = sim.get("window_start_s")
    return float(sim.get("duration_s", 0.5)), int(sim.get("steps", 2000)), None if start is None else float(start)


#: files the fit never sees (configs/): a drivetrain, a planetary gearbox, motor starts, excited, stiff, rattling
HELD_OUT_FILES = ("concrete_mixer_drivetrain", "wind_turbine_gearbox", "motor_soft_start", "conveyor_motor",
                  "concrete_mixer_te", "mixer_time_varying_backlash", "extreme/stiff_hertz_100x",
                  "extreme/rattle_zero_load")
#: what the generator may change in a held-out file (one draw per variant)
VARIATIONS = (
    ("iso law", ["contact.stiffness=iso6336", "contact.exponent=1.5", "contact.damping_ratio=0.05"]),
    ("rtol 1e-7", ["simulation.rtol=1e-7"]),
    ("rtol 1e-5", ["simulation.rtol=1e-5"]),
    ("duration x1.5", ["@duration=1.5"]),
    ("duration x0.5", ["@duration=0.5"]),
)
VARIANTS_PER_FILE = 2
SEED = 33


def _name(p: Path) -> str:
    return p.stem if p.parent.name == "configs" else f"{p.parent.name}/{p.stem}"


def _expand(path: Path, sets: list[str]) -> list[str]:
    """``@duration=F``: the file's simulation.duration_s (and steps, and a window start it sets) times F."""
    out = []
    for s in sets:
        if s.startswith("@duration="):
            f = float(s.split("=", 1)[1])
            duration, steps, start = _duration(path)
            out += [f"simulation.duration_s={duration * f!r}", f"simulation.steps={max(10, int(steps * f))}"]
            out += [] if start is None else [f"simulation.window_start_s={start * f!r}"]
        else:
            out.append(s)
    return out


def scene_sets() -> dict[str, list[tuple[str, Path, list[str]]]]:
    """{"fit": [...], "held-out": [...]}: (name, file, --set overrides) each (module text)."""
    files = sorted((ROOT / "configs").glob("*.toml")) + sorted((ROOT / "configs" / "extreme").glob("*.toml"))
    fit = [(_name(p), p, []) for p in files if _name(p) not in HELD_OUT_FILES]
    rng = random.Random(SEED)
    held = []
    for p in files:
        if _name(p) not in HELD_OUT_FILES:
            continue
        held.append((_name(p), p, []))
        for label, sets in rng.sample(VARIATIONS, VARIANTS_PER_FILE):
            held.append((f"{_name(p)} ({label})", p, _expand(p, sets)))
    return {"fit": fit, "held-out": held}
