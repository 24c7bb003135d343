"""``gearcli simulate``: solver wrapper, method choice, steady-state statistics (docs/physics.md, "Torsional model").

- ``solver``  one loop around scipy's ODE solvers: tolerances, samples, counters, failures, restarts at
              the ramp ends
- ``guards``  cost budget from the scene, explicit-method feasibility, energy watch, force-noise warning
- ``choice``  ``method = "auto"`` from the linearised stiffness
- ``stats``   steady window, channel statistics, per-stage dynamics, warnings
- ``run``     ``run_simulation`` (design file + design) and ``simulate_model`` (an assembled model)
"""

from gearcli.simulate.run import run_simulation, simulate_model

__all__ = ["run_simulation", "simulate_model"]
