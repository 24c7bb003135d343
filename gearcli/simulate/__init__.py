"""``gearcli simulate``: solver wrapper, method choice, steady-state statistics (docs/tour.md "The model, in one paragraph").

- ``solver``  one loop around scipy's ODE solvers: tolerances, samples, counters, failures, restarts at
              the ramp ends
- ``guards``  cost budget from the scene, explicit-method feasibility, energy watch, force-noise warning
- ``choice``  ``method = "auto"`` from the linearised stiffness
- ``stats``   steady window, channel statistics, per-stage dynamics, warnings
- ``estimate`` the error estimate of the window statistics (a check pass at 10x rtol)
- ``run``     ``run_simulation`` (design file + design) and ``simulate_model`` (an assembled model)

``run_simulation`` and ``simulate_model`` are imported on first use (a lazy import for start-up time, hiding
no cycle), so that importing one of the light modules here does not pull in scipy. The registry of methods
lives in the leaf core (:mod:`gearcli.core.methods`).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:  # the precise signatures for the type checker; at run time they load on first use
    from gearcli.simulate.run import run_simulation, simulate_model

__all__ = ["run_simulation", "simulate_model"]


def __getattr__(name: str) -> object:
    if name in __all__:
        from gearcli.simulate import run  # lazy: scipy, the package's names load on first use (PEP 562)

        return getattr(run, name)
    raise AttributeError(name)
