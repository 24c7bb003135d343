"""Guard rails of the integration: a cost budget from the scene, a feasibility check for explicit
methods, and an energy watch that stops a diverging run before it reaches NaN.

Budget (the constants: :mod:`gearcli.core.cost`). An adaptive method's cost follows the number of oscillation periods it must resolve or stay
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
starts, naming the element (mesh, coupling or flexible shaft) that makes the scene stiff and the fix. Below it the explicit run goes ahead,
with the stiffness warning of :mod:`gearcli.simulate.run`.

Energy. With non-negative damping the model cannot create energy: kinetic plus stored elastic energy
can grow at most by the net work the drive and the load put in (docs/physics.md, "Torsional model"; the damping loss
and the tensile clamp only remove energy). :class:`EnergyWatch` checks this every few steps from the
state and its work quadratures and flags a growth beyond ``ENERGY_MARGIN`` of the scene's energy scale,
the signature of a numerical instability, long before the state overflows.
"""

from __future__ import annotations

import math

import numpy as np

from gearcli import diagnostics as dg
from gearcli.core import cost
from gearcli.core.cost import (
    CAP,
    EXPLICIT_CAP,
    FLOOR,
    PROJECTION_AFTER_S,
    PROJECTION_LIMIT,
    WORK_CAP_S,
    accuracy_factor,
    duration_text,
    nfev_budget,
    priced_work_s,
)
from gearcli.core.memo import remember
from gearcli.core.methods import IMPLICIT_METHOD, method
from gearcli.core.records import record
from gearcli.diagnostics import Diagnostic
from gearcli.errors import SimulationError
from gearcli.model import Layout, TorsionalModel
from gearcli.model.linear import Linearisation, static_forces
from gearcli.model.outputs import stored_energy
from gearcli.simulate.choice import STIFFNESS_LIMIT, Choice, element_name

# the prices and budgets live in gearcli.core.cost (one module for every cost constant)
__all__ = ["CAP", "EXPLICIT_CAP", "FLOOR", "PRICE_S", "PROJECTION_AFTER_S", "PROJECTION_LIMIT", "WORK_CAP_S",
           "EnergyWatch", "accuracy_factor", "energy_watch", "force_noise", "force_noise_warnings", "nfev_budget",
           "over_budget", "priced_work_s", "require_feasible"]
PRICE_S = cost.PRICE_S["python"]  # the work budget's prices, on either engine
ENERGY_MARGIN = 0.1  # of the scene's energy scale
ENERGY_CHECK_EVERY = 16  # accepted steps between energy checks (divergence grows geometrically)


def over_budget(work_s: float, t: float, t_start: float, t_end: float,
                speedup: float = 1.0) -> tuple[str, str] | None:
    """Why a run that has used ``work_s`` priced seconds and reached ``t`` of [t_start, t_end] must stop now:
    ``("spent", why)`` when its budget is used up, ``("projected", why)`` when its pace projects to over
    :data:`PROJECTION_LIMIT` times the budget (the text names the duration that would fit); else None.
    ``speedup``: a compiled run's (:func:`gearcli.core.cost.compiled_speedup`): its budget is that many times
    the priced work, its projection judged against that budget (a run the compiled engine finishes within its
    budget is not refused for what it would cost on scipy), and the text in its own seconds."""
    cap = WORK_CAP_S * speedup
    if work_s > cap:
        return "spent", f"it used its computing budget of ~{WORK_CAP_S:g} s"
    if work_s > PROJECTION_AFTER_S:
        done = (t - t_start) / (t_end - t_start) if t_end > t_start else 1.0
        projected = work_s / done if done > 0 else math.inf
        if projected > PROJECTION_LIMIT * cap:
            fit = t_start + (t - t_start) * cap / work_s
            return "projected", (f"at its pace ({100 * done:.2g} % of the run after ~{work_s / speedup:.2g} s of "
                                 f"computing) it would need about {duration_text(projected / speedup)}, over "
                                 f"{PROJECTION_LIMIT:g}x the budget of ~{WORK_CAP_S:g} s; simulation.duration_s ≤ "
                                 f"{fit:.3g} s would fit")
    return None


def require_feasible(choice: Choice, budget: int) -> None:
    """Refuse an explicit method whose stability limit alone would exceed the budget (or EXPLICIT_CAP)."""
    if method(choice.method).implicit:
        return
    needed = choice.explicit_evaluations(choice.method)
    budget = min(budget, EXPLICIT_CAP)
    if needed <= budget:
        return
    freqs = choice.at_operating_point.natural_frequencies_Hz
    f = float(freqs[-1]) if freqs.size else 0.0
    lin, fastest = _fastest_eigenvalue(choice)
    if abs(fastest.imag) < DECAY_SHARE * abs(fastest):  # a decay, not a vibration: a damper sets it, no stiffness
        cause = (f"its fastest motion is a decay at {abs(fastest):.3g} 1/s (time constant {1.0 / abs(fastest):.2g} s, "
                 f"{abs(fastest) / (2.0 * math.pi * f) if f > 0 else math.inf:.2g}x its highest mode's 2 pi f): "
                 f"{_fastest_damper(lin, choice.layout)}'s damping against the light inertias it joins makes it")
    else:
        cause = f"{choice.stiff_element[0]} makes it"
    raise SimulationError(
        f"method = \"{choice.method}\" cannot integrate this scene: {cause} "
        f"{choice.indicator / STIFFNESS_LIMIT:.2g}x stiffer than an explicit method affords (highest mode "
        f"{f:.3g} Hz, max|λ|·T = {choice.indicator:.3g}, limit {STIFFNESS_LIMIT:.0e}); stability alone would take "
        f"{needed:.2g} right-hand-side evaluations, over the explicit budget of {budget:.2g}: use method = "
        f"\"{IMPLICIT_METHOD}\" (or \"auto\")")


#: the imaginary part, as a share of |lambda|, below which the scene's fastest eigenvalue is a decay (damping ratio
#: above sqrt(1 - 0.5^2) = 0.87) rather than a vibration of a mode
DECAY_SHARE = 0.5


def _fastest_eigenvalue(choice: Choice) -> tuple[Linearisation, complex]:
    """The linearisation (of the two the indicator max|lambda| T takes) with the eigenvalue of largest |lambda|, and
    that eigenvalue (0 if none)."""
    lin = max((choice.at_full_load, choice.at_operating_point), key=lambda x: x.max_abs_eigenvalue)
    values = np.asarray(lin.eigenvalues, dtype=complex).ravel()
    return lin, complex(values[int(np.argmax(np.abs(values)))]) if values.size else 0j


def _fastest_damper(lin: Linearisation, lay: Layout) -> str:
    """The connector whose damping against the inertias it joins decays fastest (its c times the sum of its levers
    squared over those inertias, the rate c / m of a damper on a free mass), in a message's words."""
    rates = [float(lin.damping[c]) * sum(lever**2 / lay.inertias[b] for lever, b in zip(x.levers, x.bodies, strict=True)
                                         if lay.state.omega(b) is not None)
             for c, x in enumerate(lay.connectors)]
    return element_name(lay, int(np.argmax(rates)))


@record
class EnergyReport:
    """Energy the integration created beyond the net work put in, and its scale."""

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
        """Kinetic energy of the rigid chain at nominal speed plus elastic energy at full static load
        (each element's own stored energy at its static deflection; meshes at their mean stiffness): the model's
        own, computed once per layout (every integration of a run, its settle runs and shots, starts a watch)."""
        lay = self.model.layout
        cache = lay.__dict__.setdefault("_energy_scale", [])
        if not cache:
            cache.append(_nominal_scale(lay))
        return cache[0]

    def _work(self, y: np.ndarray) -> float:
        """W_in - W_load (J) from the quadrature states."""
        st = self.model.layout.state
        return float(y[st.quadrature("input_work_J")] - y[st.quadrature("load_work_J")])

    def _stored(self, t: float, y: np.ndarray) -> float:
        """Kinetic energy + elastic energy of constant-stiffness meshes + work done on time-varying springs."""
        lay = self.model.layout
        stored = stored_energy(lay, t, y)  # the elements' own laws, one sample (the signals held once inside)
        i_tv = lay.state.quadrature("elastic_work_tv_J")
        if i_tv is not None:
            stored += float(y[i_tv])
        return stored

    def check(self, t: float, y: np.ndarray) -> EnergyReport:
        created = (self._stored(t, y) - self.e0) - (self._work(y) - self.w0)
        return EnergyReport(created, max(self.scale, abs(self._work(y) - self.w0)))

    def message(self, report: EnergyReport) -> str:
        return (f"the energy in the gear train grew by {report.created_J:.3g} J more than the drive and the load put "
                f"in ({report.created_J / report.scale_J:.2g}x the scene's energy scale of {report.scale_J:.3g} J)")


def _nominal_scale(lay: Layout) -> float:
    """:meth:`EnergyWatch._nominal_scale` of a layout."""
    rho = np.array([b.ratio for b in lay.bodies])
    ke = 0.5 * float(np.asarray(lay.inertias) @ (rho * lay.drive.speed_rad_s) ** 2)
    u = 0.0
    for x, f in zip(lay.connectors, np.abs(static_forces(lay)), strict=True):
        el = x.element
        # all it reads: the element's three laws, its parameters and the force (a sweep's points share their load)
        key = (el.linear_row, el.static_deflection, el.potential, x.params, f)
        found = _STATIC_POTENTIALS.get(key)
        if found is None:
            P = el.linear_row(x.params, 1.0)
            found = remember(_STATIC_POTENTIALS, key, el.potential(P, el.static_deflection(P, f), 0.0), cap=64)
        u += found
    return max(ke + u, np.finfo(float).tiny)


#: a connector's stored energy at its static force (:func:`_nominal_scale`), by its element's laws (pure functions:
#: a replaced one is another key), its parameter row and the force
_STATIC_POTENTIALS: dict[tuple, float] = {}


def energy_watch(model: TorsionalModel, y0: np.ndarray, t0: float = 0.0) -> EnergyWatch | None:
    """An energy watch for the run from ``(t0, y0)``, or None when the energy scale is degenerate (nothing moves)."""
    watch = EnergyWatch(model, y0, t0)
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
    (configs/extreme/stiff_linear_10000x.toml), where BDF forced at rtol 1e-6 strays 0.85x the static force from the
    rigid-body answer, LSODA 0.33x, while Radau stays within 0.4 % (DOP853 strayed 15x before its steps were capped
    at its stability limit; now 0.4 %: :func:`force_noise_warnings`).
    """
    lay = choice.layout
    lin, full = choice.at_operating_point, choice.at_full_load
    J = np.asarray(lay.inertias)
    w = np.array([b.ratio for b in lay.bodies]) * lay.drive.speed_rad_s
    out = np.zeros(len(lay.stage_conn))
    for k, c in enumerate(lay.stage_conn):
        x = lay.connectors[c]
        rp, rg = x.ra, x.rb
        mobility = (rp**2 / J[x.a] if lay.state.omega(x.a) is not None else 0.0) + rg**2 / J[x.b]
        force = abs(float(full.forces[c])) or abs(float(lin.forces[c]))  # static, else run-up
        if force > 0 and lin.stiffness[c] > 0:
            v_tol = rtol * (rp * abs(w[x.a]) + rg * abs(w[x.b]))
            out[k] = v_tol * math.sqrt(lin.stiffness[c] / mobility) / force
    return out


def force_noise_warnings(choice: Choice, rtol: float) -> list[Diagnostic]:
    """Warn when the tolerance cannot resolve a mesh force and the method will not damp the noise away: BDF and
    LSODA. Not Radau (it damps what it cannot resolve), and not an explicit method: its steps are capped at its
    stability limit on the stiffest mode (:func:`gearcli.simulate.choice.stability_step`), so the stiff mode is not
    sustained at the tolerance's level, and the noise :func:`force_noise` predicts does not arise (DOP853 on
    stiff_linear_10000x at rtol 1e-6: predicted 19 % of stage 1's force, its window min 0.4 % off an exact linear
    solution; a two-stage chain at rtol 1e-2: predicted 120 %, 1e-9 off); its check pass measures what it misses,
    and the ``stiff_for_explicit`` warning names the cheaper method."""
    if choice.method in DAMPS_UNRESOLVED or not method(choice.method).implicit:
        return []
    noise = force_noise(choice, rtol)
    return [dg.warning(dg.FORCE_NOISE, f"stage {k + 1}: at rtol {rtol:g} the shaft-speed tolerance resolves this "
                       f"mesh's force only to ~{100 * x:.2g} % (the mesh is very stiff for its inertias); "
                       f"{choice.method} may show spurious force noise of that size or more: use method = "
                       f"\"{IMPLICIT_METHOD}\" (or \"auto\")", stage=k + 1, relative_noise=float(x))
            for k, x in enumerate(noise) if x > NOISE_WARN]
