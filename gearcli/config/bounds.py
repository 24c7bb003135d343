"""Resource bounds stated and enforced before a run starts (docs/design-file.md, "Limits").

Memory. A simulation holds its output samples in memory (the state, the channels, then the text
written). The peak is about ``samples x values per sample x bytes per value``; the bytes per value were
measured at the steps cap on the seed reducer (docs/numerics.md, "Numerical robustness": CSV 1.6 GB, JSON 0.9 GB,
JSON with ``--series`` 5.6 GB for 2e6 x 19 values) and are rounded up here. A run whose estimate exceeds
:func:`memory_limit_bytes` is refused with the estimate and the ``simulation.steps`` that would fit.

Cost. An adaptive integrator's cost follows ``max|lambda| T``: the fastest oscillation of the linearised
train times the duration (gearcli.simulate.guards). Estimated here from the design alone (no scipy): each
mesh's own angular frequency ``sqrt(k (r_b1^2 / J_1 + r_b2^2 / J_2))`` (a speed-driven input shaft without a
motor coupling has no degree of freedom: J_1 infinite, as in the model) with the linearised stiffness at
the static load (at least the stiffness of a 1 um approach, so an unloaded mesh is not free), the mesh
frequency when the stiffness varies in time, times the highest harmonic of a mesh excitation
(transmission error, stiffness harmonics), the highest input torque-ripple order times the input speed and
the highest load-fluctuation frequency. At ~30 evaluations per unit (the worst measured, see guards),
a run whose estimate is absurd (:data:`ABSURD_EVALUATIONS`) is refused up front, naming the figure and the
setting to change.
"""

from __future__ import annotations

import math
import os

from gearcli.config.schema_rules import MIN_DURATION_S
from gearcli.core.text import rounded_down, shorten
from gearcli.errors import ConfigError, ResourceError
from gearcli.stages import kinds

MEMORY_LIMIT_VARIABLE = "GEARCLI_MEMORY_LIMIT_MB"
DEFAULT_MEMORY_LIMIT_MB = 2048.0
MAX_MEMORY_LIMIT_MB = 2.0**40  # a petabyte: beyond it the figure is a typo, not a machine


def memory_limit_bytes() -> int:
    """The memory bound: ``GEARCLI_MEMORY_LIMIT_MB`` (MiB, a finite number > 0) or 2048 MiB when unset. Anything
    else (empty, garbage, nan, inf, 0, negative) is a usage error naming the variable (exit 2)."""
    raw = os.environ.get(MEMORY_LIMIT_VARIABLE)
    if raw is None:
        return int(DEFAULT_MEMORY_LIMIT_MB * 2**20)
    try:
        mb = float(raw.strip())
    except ValueError:
        mb = math.nan
    if not (math.isfinite(mb) and 0 < mb <= MAX_MEMORY_LIMIT_MB):
        raise ConfigError(f"must be a number of MiB, > 0 and ≤ {MAX_MEMORY_LIMIT_MB:.0f}, got {shorten(repr(raw), 60)} "
                          f"(unset it for the default {DEFAULT_MEMORY_LIMIT_MB:.0f})",
                          source=f"environment variable {MEMORY_LIMIT_VARIABLE}")
    return max(1, int(mb * 2**20))
BYTES_PER_VALUE = {"csv": 48, "json": 28, "series": 160, "table": 28}  # measured peaks, rounded up
EVALUATIONS_PER_UNIT = 30.0  # right-hand sides per unit of max|lambda| T at rtol 1e-6 (guards.COST_PER_UNIT)
MAX_EVALUATIONS = 5e6  # one run: ~30 s of right-hand sides on a 2-core machine (guards.CAP)
#: Estimates beyond this are refused as absurd (a unit mistake, not a scene). The estimate is an upper bound
#: for explicit methods; implicit ones step over fast modes that are not excited (configs/extreme/
#: unequal_inertias.toml: estimate 2.8e8, run within the 5e6 budget), so the margin is 100x the budget, and
#: between the two the run's own budget stops it.
ABSURD_EVALUATIONS = 100 * MAX_EVALUATIONS


def values_per_sample(n_stages: int) -> int:
    """time, one speed per shaft, the input torque, five channels per stage, and the state (2 per shaft)."""
    shafts = n_stages + 1
    return 1 + shafts + 1 + 5 * n_stages + 2 * shafts


def memory_estimate_bytes(steps: int, n_stages: int, fmt: str, series: bool) -> float:
    per_value = BYTES_PER_VALUE["series" if (fmt == "json" and series) else fmt if fmt in BYTES_PER_VALUE else "json"]
    return (steps + 1) * values_per_sample(n_stages) * per_value


#: ``steady = "periodic"``: the statistics periods are sampled ``steps`` times, or more when the fastest
#: excitation needs it (64 samples per its period), up to this many (gearcli.simulate.periodic)
PERIODIC_STATISTICS_SAMPLES = 100_000


def output_samples(sim) -> int:
    """Output samples of a run with ``[simulation]`` settings ``sim``, at most: ``steps`` (+1) for a window
    run; for a periodic one the run-up (at most ``steps``) and the statistics periods."""
    if getattr(sim, "steady", "window") == "periodic":
        return sim.steps + max(sim.steps, PERIODIC_STATISTICS_SAMPLES)
    return sim.steps


def steps_that_fit(sim, samples: int) -> int:
    """The largest ``simulation.steps`` whose run holds at most ``samples`` output samples (the inverse of
    :func:`output_samples`; 0 when none does: a periodic run holds its statistics samples whatever its steps)."""
    if getattr(sim, "steady", "window") == "periodic":
        return samples // 2 if samples >= 2 * PERIODIC_STATISTICS_SAMPLES else max(0, samples - PERIODIC_STATISTICS_SAMPLES)
    return max(0, samples)


def _gib(n: float) -> str:
    return f"{n / 2**30:.3g} GiB" if n >= 2**30 else f"{n / 2**20:.3g} MiB"


def check_memory(cfg, *, fmt: str, series: bool, source: str, steps: int | None = None) -> None:
    """The one memory rule of every run a command makes (simulate, report, each sweep point, each life
    point): its output samples (``steps``, default the file's) against :func:`memory_limit_bytes`."""
    limit = memory_limit_bytes()
    given = steps is not None  # the caller's samples (a life duty point's), not the file's steps
    samples, n = steps if steps is not None else output_samples(cfg.simulation), len(cfg.stage)
    need = memory_estimate_bytes(samples, n, fmt, series)
    if need <= limit:
        return
    most = int(limit // memory_estimate_bytes(0, n, fmt, series)) - 1  # samples: (samples + 1) x the bytes of one
    fit = most if given else steps_that_fit(cfg.simulation, most)
    how = " or leave out --series" if fmt == "json" and series else ""
    held = ("" if given or cfg.simulation.steady != "periodic" else
            f" (steady = \"periodic\": the run-up's steps and {PERIODIC_STATISTICS_SAMPLES} statistics samples)")
    raise ResourceError(
        f"{source}: simulation.steps: {samples} samples{held} x {values_per_sample(n)} values would need about "
        f"{_gib(need)} of memory, over the limit of {_gib(limit)}; "
        + (f"set simulation.steps ≤ {fit}{how} (or raise {MEMORY_LIMIT_VARIABLE})" if fit >= 1 else
           f"no run fits in it: raise {MEMORY_LIMIT_VARIABLE}"
           + ("" if given or cfg.simulation.steady != "periodic" else ' or use steady = "window"')))


def fastest_rad_s(cfg, design) -> float:
    """The fastest angular frequency the integrator must follow, from the design (see the module text)."""
    inertia = [sh.inertia_kg_m2 for sh in design.shafts]
    if _input_prescribed(cfg):
        inertia[0] = math.inf  # no degree of freedom: infinitely heavy, as the model's damping sizes it (model.assembly)
    fastest = 0.0
    for k, st in enumerate(design.stages):  # each stage as its kind puts it in the model (gearcli.stages)
        kind = kinds.facet(kinds.kind_of(st), "design")
        fastest = max(fastest, kind.fastest_rad_s(cfg, st, k, inertia[k], inertia[k + 1]))  # type: ignore[attr-defined]
    fastest = max([fastest] + [r.order * cfg.input.speed_rad_s_value for r in cfg.input.torque_ripple]
                  + [2 * math.pi * f.frequency_Hz for f in cfg.load.fluctuation])
    return fastest


def _input_prescribed(cfg) -> bool:
    """Shaft 1 follows the speed profile itself (``drive = "speed"`` without a motor on a coupling): its motion is
    given, so its inertia takes part in no vibration; a coupled motor leaves it free (the motor follows the profile)."""
    return cfg.input.drive == "speed" and cfg.input.coupling_stiffness_Nm_rad is None


def evaluations_estimate(cfg, design, rtol: float) -> float:
    indicator = max(1.0, fastest_rad_s(cfg, design) * cfg.simulation.duration_s)
    return EVALUATIONS_PER_UNIT * indicator * max(1.0, (1e-6 / rtol) ** 0.2)


def check_cost(cfg, design, *, source: str) -> None:
    """Refuse a run whose estimate is absurd (over :data:`ABSURD_EVALUATIONS`), before it starts."""
    sim = cfg.simulation
    total = evaluations_estimate(cfg, design, sim.rtol)
    if math.isfinite(total) and total <= ABSURD_EVALUATIONS:
        return
    fit = sim.duration_s * ABSURD_EVALUATIONS / total if math.isfinite(total) and total > 0 else 0.0
    shorter = f"set simulation.duration_s ≤ {rounded_down(fit):.3g}, or check" if fit >= MIN_DURATION_S else \
        f"no simulation.duration_s from its least {MIN_DURATION_S:g} s fits: check"  # a limit the schema refuses
    raise ResourceError(
        f"{source}: simulation.duration_s: this run would need about {total:.2g} right-hand-side evaluations "
        f"(fastest oscillation {fastest_rad_s(cfg, design) / (2 * math.pi):.3g} Hz over {sim.duration_s:g} s), "
        f"over the limit of {ABSURD_EVALUATIONS:.2g}; {shorter} the speeds, loads, mesh stiffnesses and inertias "
        "for a unit mistake")


def check_run_budget(cfg, design, *, fmt: str, series: bool, source: str) -> None:
    """``gearcli simulate``: memory and cost, before scipy is even imported."""
    check_memory(cfg, fmt=fmt, series=series, source=source)
    check_cost(cfg, design, source=source)
