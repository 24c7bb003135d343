"""Guard rails of the integration: a cost budget from the scene, a feasibility check for explicit
methods, and an energy watch that stops a diverging run before it reaches NaN.

Budget. An adaptive method's cost follows the number of oscillation periods it must resolve or stay
stable over, i.e. the stiffness indicator ``max|lambda| T`` of the linearised scene
(:mod:`gearcli.simulate.choice`). Measured on the example scenes and the extreme catalogue
(``benchmarks/robustness.py``, ``benchmarks/bench_simulate.py``) every method needs at most ~30
evaluations per unit of ``max|lambda| T`` at rtol 1e-6 (DOP853 on a rattling gear train: 26; Radau on
time-varying stiffness: 18), and roughly ``(1e-6 / rtol)^(1/5)`` times more at tighter tolerances. The
budget allows ``HEADROOM`` = 10 times that, never less than ``FLOOR`` (short, soft runs) nor more than
``CAP`` (~30 s of right-hand sides on a 2-core machine). A run that needs more is not converging: contacts
chattering, a step size collapsing, or an explicit method grinding through a stiff scene.

Explicit methods on stiff scenes. Stability alone costs an explicit method ``EVALS_PER_STEP / R
max|lambda| T`` evaluations (R its stability radius along the imaginary axis). When that exceeds
``EXPLICIT_CAP`` (1e6 evaluations, ~10 s; Radau does such scenes in ~1e4) the run is refused before it
starts, naming the mesh that makes the scene stiff and the fix. Below it the explicit run goes ahead,
with the stiffness warning of :mod:`gearcli.simulate.run`.

Energy. With non-negative damping the model cannot create energy: kinetic plus stored elastic energy
can grow at most by the net work the drive and the load put in (docs/physics.md, "Torsional model"; the damping loss
and the tensile clamp only remove energy). :class:`EnergyWatch` checks this every few steps from the
state and its work quadratures and flags a growth beyond ``ENERGY_MARGIN`` of the scene's energy scale,
the signature of a numerical instability, long before the state overflows.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional

import numpy as np

from gearcli.errors import SimulationError
from gearcli.model import TorsionalModel
from gearcli.model.linear import static_line_forces_N
from gearcli.model.outputs import kinetic_energy, potential_energy, sample
from gearcli.simulate.choice import EXPLICIT, IMPLICIT_METHOD, STIFFNESS_LIMIT, Choice
from gearcli.simulate.solver import MAX_NFEV

COST_PER_UNIT = 30.0  # evaluations per unit of max|lambda| T at rtol 1e-6 (worst measured: 26)
HEADROOM = 10.0
FLOOR = 200_000  # ~1 s of right-hand sides: never stop a short soft run early
CAP = MAX_NFEV  # 5e6: ~30 s of right-hand sides on a 2-core machine
EXPLICIT_CAP = 1_000_000  # stability-only cost beyond which an explicit method is refused (~10 s)
ENERGY_MARGIN = 0.1  # of the scene's energy scale
ENERGY_CHECK_EVERY = 16  # accepted steps between energy checks (divergence grows geometrically)


def accuracy_factor(rtol: float) -> float:
    """How much more a run at ``rtol`` costs than at 1e-6 (order-5 error control; >= 1)."""
    return max(1.0, (1e-6 / rtol) ** 0.2)


def nfev_budget(indicator: float, rtol: float) -> int:
    """Right-hand-side evaluations a run of stiffness indicator ``max|lambda| T`` may use."""
    estimate = COST_PER_UNIT * max(indicator, 1.0) * accuracy_factor(rtol)
    return int(min(CAP, max(FLOOR, HEADROOM * estimate)))


def require_feasible(choice: Choice, budget: int) -> None:
    """Refuse an explicit method whose stability limit alone would exceed the budget (or EXPLICIT_CAP)."""
    if choice.method not in EXPLICIT:
        return
    needed = choice.explicit_evaluations(choice.method)
    budget = min(budget, EXPLICIT_CAP)
    if needed <= budget:
        return
    k = choice.stiffest_mesh
    freqs = choice.at_operating_point.natural_frequencies_Hz
    f = float(freqs[-1]) if freqs.size else 0.0
    raise SimulationError(
        f"method = \"{choice.method}\" cannot integrate this scene: mesh stage {k + 1} makes it "
        f"{choice.indicator / STIFFNESS_LIMIT:.2g}x stiffer than an explicit method affords (highest mode "
        f"{f:.3g} Hz, max|λ|·T = {choice.indicator:.3g}, limit {STIFFNESS_LIMIT:.0e}); stability alone would take "
        f"{needed:.2g} right-hand-side evaluations, over the explicit budget of {budget:.2g}: use method = "
        f"\"{IMPLICIT_METHOD}\" (or \"auto\")")


@dataclass(frozen=True)
class EnergyReport:
    created_J: float  # growth of kinetic + stored energy beyond the net work put in
    scale_J: float

    @property
    def diverging(self) -> bool:
        return self.created_J > ENERGY_MARGIN * self.scale_J


class EnergyWatch:
    """Kinetic + stored elastic energy against the net work of drive and load, from one state."""

    def __init__(self, model: TorsionalModel, y0: np.ndarray, t0: float = 0.0):
        self.model = model
        self.every = ENERGY_CHECK_EVERY
        self.e0 = self._stored(t0, y0)
        self.w0 = self._work(y0)
        self.scale = max(self._nominal_scale(), abs(self.e0))

    def _nominal_scale(self) -> float:
        """Kinetic energy of the rigid train at nominal speed plus elastic energy at full static load."""
        spec, lay = self.model.spec, self.model.layout
        rho = np.asarray(spec.speed_ratios)
        ke = 0.5 * float(np.asarray(spec.inertias_kg_m2) @ (rho * spec.drive.speed_rad_s) ** 2)
        F = np.abs(static_line_forces_N(spec))
        u = sum(m.stiffness_N_m_e * (f / m.cos_beta_b / m.stiffness_N_m_e) ** ((m.exponent + 1) / m.exponent)
                / (m.exponent + 1) for m, f in zip(lay.meshes, F))
        return max(ke + u, np.finfo(float).tiny)

    def _work(self, y: np.ndarray) -> float:
        """W_in - W_load (J) from the quadrature states."""
        q = self.model.layout.i_quad
        return float(y[q] - y[q + 1])

    def _stored(self, t: float, y: np.ndarray) -> float:
        """Kinetic energy + elastic energy of constant-stiffness meshes + work done on time-varying springs."""
        lay = self.model.layout
        s = sample(lay, np.array([t]), y[:, None])
        stored = float(kinetic_energy(lay, s.omega_rad_s)[0]) + float(potential_energy(lay, s, time_varying=False)[0])
        if lay.n_tv:
            stored += float(y[lay.i_quad + 3])
        return stored

    def check(self, t: float, y: np.ndarray) -> EnergyReport:
        created = (self._stored(t, y) - self.e0) - (self._work(y) - self.w0)
        return EnergyReport(created, max(self.scale, abs(self._work(y) - self.w0)))

    def message(self, report: EnergyReport) -> str:
        return (f"the energy in the gear train grew by {report.created_J:.3g} J more than the drive and the load put "
                f"in ({report.created_J / report.scale_J:.2g}x the scene's energy scale of {report.scale_J:.3g} J)")


def energy_watch(model: TorsionalModel, y0: np.ndarray) -> Optional[EnergyWatch]:
    """An energy watch for the run, or None when the energy scale is degenerate (nothing moves)."""
    watch = EnergyWatch(model, y0)
    return watch if math.isfinite(watch.scale) and watch.scale > 0 else None


NOISE_WARN = 0.05  # predicted mesh-force noise, relative to the mesh's static (or run-up) force
DAMPS_UNRESOLVED = ("Radau",)  # L-stable with a stiffly filtered error estimate: unresolved vibration decays


def force_noise(choice: Choice, rtol: float) -> np.ndarray:
    """Per mesh, the mesh-force error the speed tolerance allows, relative to the mesh's force.

    The states are absolute shaft speeds, but a mesh force follows the deflection rate, the difference
    r_bp w_p - r_bg w_g of two pitch-line speeds. A speed error within tolerance, rtol (r_bp w_p + r_bg w_g),
    moves the mesh by that velocity, i.e. by a force of Z = sqrt(k m) times it (the mesh impedance, m the
    inertia it drives reduced to its line of action; k at the run-up load, the stiffest). Against the static
    force F (the run-up force when there is no load) this is
    rtol (r_bp w_p + r_bg w_g) sqrt(k m) / F: 3e-3 on the seed, 0.19 with 10,000x stiffer linear meshes
    (configs/extreme/stiff_linear_10000x.toml), where DOP853 forced at rtol 1e-6 strays up to 15x the static
    force from the rigid-body answer, BDF 0.85x, LSODA 0.33x, while Radau stays within 0.4 %.
    """
    spec = choice.spec
    lin, full = choice.at_operating_point, choice.at_full_load
    J = np.asarray(spec.inertias_kg_m2)
    w = np.asarray(spec.speed_ratios) * spec.drive.speed_rad_s
    first = 1 if spec.drive.kind == "speed" else 0
    out = np.zeros(len(spec.meshes))
    for k, m in enumerate(spec.meshes):
        rp, rg = m.base_radius_pinion_m, m.base_radius_gear_m
        mobility = (rp**2 / J[k] if k >= first else 0.0) + rg**2 / J[k + 1]
        force = abs(float(full.line_forces_N[k])) or abs(float(lin.line_forces_N[k]))  # static, else run-up
        if force > 0 and lin.stiffness_N_m[k] > 0:
            v_tol = rtol * (rp * abs(w[k]) + rg * abs(w[k + 1]))
            out[k] = v_tol * math.sqrt(lin.stiffness_N_m[k] / mobility) / force
    return out


def force_noise_warnings(choice: Choice, rtol: float) -> list[str]:
    """Warn when the tolerance cannot resolve a mesh force and the method will not damp the noise away."""
    if choice.method in DAMPS_UNRESOLVED:
        return []
    noise = force_noise(choice, rtol)
    return [f"stage {k + 1}: at rtol {rtol:g} the shaft-speed tolerance resolves this mesh's force only to "
            f"~{100 * x:.2g} % (the mesh is very stiff for its inertias); {choice.method} may show spurious force "
            f"noise of that size or more: use method = \"Radau\" (or \"auto\")" for k, x in enumerate(noise)
            if x > NOISE_WARN]
