"""What a run may cost: the evaluation budget every layer reads (the method choice, the guards, the engine).

A leaf module (numbers only), so that ``simulate.choice`` and ``simulate.guards`` share it without importing
each other. Evaluations of the right-hand side, scaled from the stiffness indicator max|lambda| T at rtol 1e-6
(:func:`gearcli.simulate.guards.nfev_budget`).
"""

from __future__ import annotations

COST_PER_UNIT = 30.0  # evaluations per unit of max|lambda| T at rtol 1e-6 (worst measured: 26)
HEADROOM = 10.0
FLOOR = 200_000  # ~1 s of right-hand sides: never stop a short soft run early
CAP = 5_000_000  # ~30 s of right-hand sides on a 2-core machine; then the run is called off
EXPLICIT_CAP = 1_000_000  # stability-only cost beyond which an explicit method is refused (~10 s)
