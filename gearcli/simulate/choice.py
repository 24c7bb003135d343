"""``method = "auto"``: explicit or implicit, from the linearised stiffness of the scene.

The model is linearised (:func:`gearcli.model.linearise`) twice: at full static load (the reported
natural frequencies) and at the larger of the static and the rigid-body run-up force of each mesh,
with a time-varying stiffness at its stiffest phase (a Hertz mesh stiffens with its load, so the run-up
sets the largest eigenvalue). The stiffness indicator is ``max|lambda| T`` over both, T the run length.

An explicit method needs at least ``max|lambda| T / R`` steps to stay stable, R the size of its
stability region along the direction of the eigenvalue; the mesh modes are lightly damped, so that
direction is near the imaginary axis, where R = 6.0 for DOP853 (12 evaluations per step) and only
1-3 for RK45 (6 per step): DOP853 is the cheaper explicit method per unit of stability and the more
accurate one (benchmarks/bench_simulate.py). The implicit Radau IIA (order 5, L-stable, analytic
Jacobian) costs a roughly fixed ~1-4e4 evaluation-equivalents on these scenes whatever the stiffness,
because its steps follow accuracy, not stability. The break-even measured on the seed reducer and its
stiff variants (configs/stiff_linear_mesh.toml, and stiffer ones in the benchmark) lies at
``max|lambda| T`` of about 1e4, i.e. ~2e4 explicit evaluations: auto picks DOP853 up to
``STIFFNESS_LIMIT`` and Radau above it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from gearcli.model import Linearisation, ModelSpec, linearise, static_line_forces_N
from gearcli.model.linear import peak_rigid_line_forces_N

EXPLICIT_METHOD = "DOP853"
IMPLICIT_METHOD = "Radau"
EXPLICIT = ("RK45", "DOP853")
STABILITY_RADIUS = {"DOP853": 6.0, "RK45": 2.0}  # along the imaginary axis (lightly damped modes)
EVALS_PER_STEP = {"DOP853": 12, "RK45": 6}
STIFFNESS_LIMIT = 1.0e4  # max|lambda| T above which "auto" integrates implicitly


@dataclass(frozen=True)
class Choice:
    method: str
    requested: str
    reason: str
    indicator: float  # max|lambda| T
    stiffness_ratio: float  # max|lambda| / min|lambda|
    at_full_load: Linearisation
    at_operating_point: Linearisation
    stiffest_mesh: int  # 0-based index of the mesh with the highest single-mesh frequency
    spec: ModelSpec

    @property
    def natural_frequencies_Hz(self) -> tuple[float, ...]:
        """Undamped natural frequencies to report: at full load, or at the run-up load when a mesh of
        exponent > 1 carries no static load (its linear stiffness would be 0); zero modes left out."""
        unloaded = any(m.exponent > 1 and f == 0 for m, f in zip(self.spec.meshes, self.at_full_load.line_forces_N))
        lin = self.at_operating_point if unloaded else self.at_full_load
        return tuple(float(f) for f in lin.natural_frequencies_Hz if f > 0)

    def explicit_evaluations(self, method: str = EXPLICIT_METHOD) -> float:
        """Fewest right-hand-side evaluations an explicit method needs for stability alone."""
        return EVALS_PER_STEP[method] * self.indicator / STABILITY_RADIUS[method]


def _stiffest_mesh(lin: Linearisation, spec: ModelSpec) -> int:
    """The mesh whose own mode (its stiffness against the two inertias it joins) is fastest."""
    first = 1 if spec.drive.kind == "speed" else 0
    J = spec.inertias_kg_m2
    own = []
    for k, m in enumerate(spec.meshes):
        mobility = (m.base_radius_pinion_m**2 / J[k] if k >= first else 0.0) + m.base_radius_gear_m**2 / J[k + 1]
        own.append(lin.stiffness_N_m[k] * mobility)
    return int(np.argmax(own))


def choose_method(spec: ModelSpec, duration_s: float, requested: str) -> Choice:
    """The method to run and why (``requested`` other than "auto" is kept, with the indicator)."""
    static = static_line_forces_N(spec)
    full = linearise(spec, static)
    operating = np.maximum(np.abs(static), peak_rigid_line_forces_N(spec, duration_s))
    op = linearise(spec, operating, stiffest_phase=True)
    lam = max(full.max_abs_eigenvalue, op.max_abs_eigenvalue)
    low = min((x for x in (full.min_abs_eigenvalue, op.min_abs_eigenvalue) if x > 0), default=0.0)
    indicator = lam * duration_s
    ratio = lam / low if low > 0 else math.inf
    summary = f"max|λ|·T = {indicator:.3g}"
    if requested != "auto":
        method, reason = requested, f"as requested ({summary})"
    elif indicator <= STIFFNESS_LIMIT:
        method = EXPLICIT_METHOD
        reason = f"{summary} ≤ {STIFFNESS_LIMIT:.0e}: explicit {method}"
    else:
        method = IMPLICIT_METHOD
        reason = f"{summary} > {STIFFNESS_LIMIT:.0e}: implicit {method} with the analytic Jacobian"
    return Choice(method, requested, reason, indicator, ratio, full, op, _stiffest_mesh(op, spec), spec)
