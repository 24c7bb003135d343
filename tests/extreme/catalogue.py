"""The extreme-scene catalogue: one spec per file in configs/extreme/, and the checks that judge a run.

Shared by ``tests/extreme/test_catalogue.py`` (pytest, one test per scene) and
``benchmarks/robustness.py`` (the README table), so the two can never disagree on what is checked or
how tightly. It lives under tests/ because it is a test oracle, not product code; the benchmark loads
it by path.

Every check compares the simulation with an independent expectation (:mod:`handcalc`, from the TOML
alone) or with a conservation law evaluated by this module from the output channels, never with a
number the code printed before. Each spec entry states its tolerance and why it is that size. The
common checks applied to every scene: the run finishes (``status`` 0) with the method ``"auto"`` is
expected to pick, every channel is finite, and ``nfev`` stays below a ceiling of ~3x the measured cost
(measured with scipy 1.17 on the reference machine; the ceilings catch a cost regression, not noise).
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from handcalc import Train, read

from gearcli.io.channels import named

ROOT = Path(__file__).resolve().parents[2]
SCENES_DIR = ROOT / "configs" / "extreme"
DEG = math.pi / 180.0


# --------------------------------------------------------------------------------------------- spec
@dataclass(frozen=True)
class Check:
    kind: str  # a key of CHECKS
    tol: float
    reason: str
    arg: object = None  # kind-specific (expected flanks, warning text, ...)


@dataclass(frozen=True)
class Scene:
    name: str  # configs/extreme/<name>.toml
    method: str  # what method = "auto" must pick
    nfev_ceiling: int  # ~3x measured
    checks: tuple[Check, ...]
    slow: bool = False  # > ~2 s: marked, still run in CI

    @property
    def path(self) -> Path:
        return SCENES_DIR / f"{self.name}.toml"


@dataclass
class Outcome:
    kind: str
    value: float
    tol: float
    ok: bool
    text: str  # "quantity = value (tol)"


@dataclass
class Run:
    scene: Scene
    train: Train
    result: object  # gearcli SimulationResult
    wall_s: float
    outcomes: list[Outcome] = field(default_factory=list)

    @property
    def ok(self) -> bool:
        return all(o.ok for o in self.outcomes)


# ------------------------------------------------------------------------------------ the channels
class Series:
    """Output channels of a run, in SI, with the steady window and trapezoid means."""

    def __init__(self, result, train: Train):
        self.t = result.time_s
        self.ch = named(result)
        self.n_stages = len(train.stages)
        lo, hi = result.window_s
        self.win = (self.t >= lo - 1e-12) & (self.t <= hi + 1e-12)

    def speed(self, shaft: int) -> np.ndarray:  # 1-based shaft, rad/s
        return self.ch[f"shaft{shaft}_speed_deg_s"] * DEG

    def stage(self, k: int, what: str) -> np.ndarray:  # 0-based stage
        return self.ch[f"stage{k + 1}_{what}"]

    def mean(self, x: np.ndarray) -> float:
        """Time average over the window (trapezoid: the samples are equally spaced, the ends half-weighted)."""
        t, y = self.t[self.win], x[self.win]
        return float(np.trapezoid(y, t) / (t[-1] - t[0]))

    @property
    def window_length(self) -> float:
        t = self.t[self.win]
        return float(t[-1] - t[0])

    def at_window_ends(self, x: np.ndarray) -> tuple[float, float]:
        y = x[self.win]
        return float(y[0]), float(y[-1])


# ------------------------------------------------------------------------------------------ checks
def worst_stage(s: Series, per_stage) -> tuple[float, str]:
    """The largest (error, text) of ``per_stage(k)`` over the stages (the last one on a tie)."""
    worst, text = 0.0, ""
    for k in range(s.n_stages):
        err, what = per_stage(k)
        if err >= worst:
            worst, text = err, f"stage {k + 1}: {what}"
    return worst, text


def check_ratio(s: Series, train: Train, c: Check) -> tuple[float, str]:
    """Rigid-body kinematics: mean w_in / mean w_out over the window = product of the tooth ratios."""
    ratio = s.mean(s.speed(1)) / s.mean(s.speed(s.n_stages + 1))
    return abs(ratio / train.total_ratio - 1.0), f"ratio {ratio:.7g} vs z-product {train.total_ratio:.7g}"


def predicted_mean_tangential(s: Series, train: Train) -> list[float]:
    """Mean F_t of every stage over the window from Newton's law on the driven shafts, worked from the
    output shaft back: J_n dw_n/dt = F_t,n r_g,n - T_L and J_{k+1} dw_{k+1}/dt = F_t,k r_g,k - F_t,k+1 r_p,k+1,
    averaged over the window (T_L constant there). With a still train it is the static F_t; ringing
    adds only the momentum change J dw over the window, taken from the speed channels' ends."""
    J, n, T = train.shaft_inertias, s.n_stages, s.window_length
    taken = float(train.load_torque_Nm(s.t[s.win][0]))  # N m taken off the shaft: the load (ramps are over)
    out = [0.0] * n
    for k in range(n - 1, -1, -1):  # shaft k+2 (1-based) carries gear k and pinion k+1
        w0, w1 = s.at_window_ends(s.speed(k + 2))
        out[k] = (taken + J[k + 1] * (w1 - w0) / T) * 1e3 / train.pitch_radius_mm(k, "gear")
        taken = out[k] * train.pitch_radius_mm(k, "pinion") / 1e3  # what pinion k takes off the shaft before
    return out


def check_force(s: Series, train: Train, c: Check) -> tuple[float, str]:
    """Force balance in the mean: window-mean F_t of every stage against Newton's law on the driven shafts
    (static F_t from the load and the pitch radii, plus the momentum change over the window)."""
    pred = predicted_mean_tangential(s, train)

    def stage(k):
        mean = s.mean(s.stage(k, "tangential_N"))
        scale = max(abs(train.static_tangential_N(k)), float(np.max(np.abs(s.stage(k, "tangential_N")[s.win]))) * 0.1)
        return abs(mean - pred[k]) / scale, (f"mean F_t {mean:.6g} N vs {pred[k]:.6g} N "
                                             f"(static {train.static_tangential_N(k):.6g} N)")
    return worst_stage(s, stage)


def check_static_force(s: Series, train: Train, c: Check) -> tuple[float, str]:
    """Window-mean F_t against the static F_t alone (no momentum correction): for scenes that settle."""
    def stage(k):
        mean, static = s.mean(s.stage(k, "tangential_N")), train.static_tangential_N(k)
        return abs(mean / static - 1.0), f"mean F_t {mean:.6g} N vs static {static:.6g} N"
    return worst_stage(s, stage)


def check_penetration(s: Series, train: Train, c: Check) -> tuple[float, str]:
    """Window-mean penetration against the static approach h_0 = (F_n / K)^(1/e) of the hand calculation."""
    def stage(k):
        mean, h0 = abs(s.mean(s.stage(k, "penetration_mm"))), train.static_approach_mm(k)
        return abs(mean / h0 - 1.0), f"mean penetration {mean:.5g} mm vs h0 {h0:.5g} mm"
    return worst_stage(s, stage)


def _energy_terms(s: Series, train: Train) -> dict[str, float]:
    """Work and energy over the run from the channels (trapezoid), J: W_in, W_load, dKE, dPE."""
    t = s.t
    w_in = float(np.trapezoid(s.ch["input_torque_Nmm"] / 1e3 * s.speed(1), t))
    w_load = float(np.trapezoid(train.load_torque_Nm(t) * s.speed(s.n_stages + 1), t))
    J = np.asarray(train.shaft_inertias)
    speeds = np.array([s.speed(i + 1) for i in range(len(J))])
    ke = 0.5 * J @ speeds**2
    pe = sum(train.potential_J(k, s.stage(k, "penetration_mm")) for k in range(s.n_stages))
    return {"W_in": w_in, "W_load": w_load, "dKE": float(ke[-1] - ke[0]), "dPE": float(pe[-1] - pe[0])}


def check_conservation(s: Series, train: Train, c: Check) -> tuple[float, str]:
    """No damping: W_in - W_load = dKE + dPE, everything from the channels and the hand calculation."""
    e = _energy_terms(s, train)
    res = e["W_in"] - e["W_load"] - e["dKE"] - e["dPE"]
    scale = max(abs(e["W_in"]), abs(e["W_load"]), abs(e["dKE"]))
    return abs(res) / scale, (f"W_in {e['W_in']:.6g} J - W_load {e['W_load']:.6g} J - dKE {e['dKE']:.6g} J "
                              f"- dPE {e['dPE']:.3g} J = {res:.3g} J")


def check_dissipation(s: Series, train: Train, c: Check) -> tuple[float, str]:
    """Damping only takes energy out: W_in - W_load - dKE - dPE >= 0. Value: the fraction of the input work
    dissipated, which must reach ``arg`` (a lower bound worked out in the scene's spec)."""
    e = _energy_terms(s, train)
    lost = (e["W_in"] - e["W_load"] - e["dKE"] - e["dPE"]) / abs(e["W_in"])
    return max(0.0, c.arg - lost), f"dissipated {lost:.3g} of the input work (expected >= {c.arg:g})"


def check_energy_residual(s: Series, train: Train, c: Check, result=None) -> tuple[float, str]:
    """The model's own energy balance residual (quadratures, docs/physics.md, "Torsional model")."""
    r = result.energy.residual_relative
    return r, f"energy residual {r:.2g}"


def check_rigid(s: Series, train: Train, c: Check) -> tuple[float, str]:
    """Stiff limit: the train moves as a rigid body, so the kinetic energy at the end and the load work
    equal those of the rigid train (hand calculation from the STEP profiles and the inertias)."""
    e = _energy_terms(s, train)
    ke_rigid = float(train.rigid_kinetic_J(s.t[-1]) - train.rigid_kinetic_J(s.t[0]))
    wl_rigid = train.rigid_load_work_J(float(s.t[-1]))
    errs = (abs(e["dKE"] / ke_rigid - 1.0), abs(e["W_load"] / wl_rigid - 1.0))
    return max(errs), (f"dKE {e['dKE']:.7g} J vs rigid {ke_rigid:.7g} J; "
                       f"W_load {e['W_load']:.7g} J vs rigid {wl_rigid:.7g} J")


def check_flanks(s: Series, train: Train, c: Check) -> tuple[float, str]:
    """Which flanks carry load: ``arg`` = (where, expected) with where "window" or "run" and expected
    "both" (penetration channel takes both signs), "back" (never positive), "drive" (never negative),
    for every stage. Value: number of stages that disagree."""
    where, expected = c.arg
    bad, spans = 0, []
    for k in range(s.n_stages):
        p = s.stage(k, "penetration_mm")
        p = p[s.win] if where == "window" else p
        lo, hi = float(p.min()), float(p.max())
        spans.append(f"[{lo:.3g}, {hi:.3g}]")
        ok = {"both": lo < 0 < hi, "back": hi <= 0 < -lo, "drive": lo >= 0 < hi}[expected]
        bad += not ok
    return float(bad), f"{expected} flanks over the {where}: penetration mm " + " ".join(spans)


def check_quasi_static(s: Series, train: Train, c: Check) -> tuple[float, str]:
    """A ramp much slower than the slowest mode is quasi-static: the run's peak |F_t| equals the peak of
    the rigid train (load plus run-up inertia, hand calculation)."""
    t = np.linspace(0.0, float(s.t[-1]), 20001)

    def stage(k):
        peak = float(np.max(np.abs(s.stage(k, "tangential_N"))))
        rigid = float(np.max(np.abs(train.rigid_tangential_N(k, t))))
        return abs(peak / rigid - 1.0), f"peak F_t {peak:.6g} N vs rigid {rigid:.6g} N"
    return worst_stage(s, stage)


def check_axial(s: Series, train: Train, c: Check) -> tuple[float, str]:
    """F_a = F_t tan(beta) at every sample (``arg`` None) — for a spur train F_a is exactly 0."""
    def stage(k):
        ft, fa = s.stage(k, "tangential_N"), s.stage(k, "axial_N")
        err = float(np.max(np.abs(fa - ft * math.tan(train.beta(k))))) / float(np.max(np.abs(ft)))
        return err, (f"max|F_a - F_t tan {math.degrees(train.beta(k)):g}°| / max|F_t|; "
                     f"mean F_a/F_t = {s.mean(fa) / s.mean(ft):.6g}")
    return worst_stage(s, stage)


def check_input_speed(s: Series, train: Train, c: Check) -> tuple[float, str]:
    """Torque drive with T_in i = T_L: no net rigid-body torque, so the mean input speed stays nominal."""
    w = s.mean(s.speed(1))
    return abs(w / train.input_speed_rad_s - 1.0), f"mean input speed {w:.8g} rad/s vs {train.input_speed_rad_s:.8g}"


def check_warning(s: Series, train: Train, c: Check, result=None) -> tuple[float, str]:
    """The run warns (``arg``: text every stage's warning contains). Value: stages without the warning."""
    missing = [k + 1 for k in range(s.n_stages)
               if not any(w.startswith(f"stage {k + 1}:") and c.arg in w for w in result.warnings)]
    return float(len(missing)), f"'{c.arg}' warned for {s.n_stages - len(missing)}/{s.n_stages} stages"


def check_damping_loss(s: Series, train: Train, c: Check, result=None) -> tuple[float, str]:
    """The damping loss relative to the input work (bounded above by ``tol`` from the law's STEP ramp)."""
    frac = result.energy.damping_loss_J / abs(result.energy.input_work_J)
    return abs(frac), f"damping loss {result.energy.damping_loss_J:.3g} J = {frac:.2g} of the input work"


CHECKS: dict[str, Callable] = {
    "ratio": check_ratio, "force": check_force, "static_force": check_static_force, "penetration": check_penetration,
    "conservation": check_conservation, "dissipation": check_dissipation, "energy_residual": check_energy_residual,
    "rigid": check_rigid, "flanks": check_flanks, "quasi_static": check_quasi_static, "axial": check_axial,
    "input_speed": check_input_speed, "warning": check_warning, "damping_loss": check_damping_loss,
}
NEEDS_RESULT = {"energy_residual", "warning", "damping_loss"}


# ----------------------------------------------------------------------------------------- running
def common_outcomes(scene: Scene, result) -> list[Outcome]:
    """The checks every scene gets: finished, the expected auto method, finite channels, cost."""
    sv = result.solver
    bad = [k for k, v in named(result).items() if not np.all(np.isfinite(v))]
    return [
        Outcome("finished", float(sv.status), 0, sv.status == 0, f"status {sv.status}"),
        Outcome("method", 0.0, 0, sv.requested_method == "auto" and sv.method in scene.method.split("|"),
                f"auto picked {sv.method} (expected {scene.method}): {sv.choice_reason}"),
        Outcome("finite", float(len(bad)), 0, not bad and len(named(result)) > 0,
                "all channels finite" if not bad else f"non-finite: {', '.join(bad)}"),
        Outcome("nfev", float(sv.nfev), scene.nfev_ceiling, sv.nfev <= scene.nfev_ceiling,
                f"nfev {sv.nfev} <= {scene.nfev_ceiling}"),
    ]


def evaluate(scene: Scene, train: Train, result) -> list[Outcome]:
    s = Series(result, train)
    out = common_outcomes(scene, result)
    for c in scene.checks:
        fn = CHECKS[c.kind]
        value, text = fn(s, train, c, result=result) if c.kind in NEEDS_RESULT else fn(s, train, c)
        out.append(Outcome(c.kind, value, c.tol, bool(value <= c.tol), f"{text}: {value:.2g} <= {c.tol:g}"))
    return out


def run_scene(scene: Scene) -> Run:
    """Load, design and simulate a scene through the library (as ``gearcli simulate`` does), then judge it."""
    from gearcli.config import load_design
    from gearcli.design import compute_design
    from gearcli.simulate import run_simulation

    loaded = load_design(str(scene.path), [])
    design = compute_design(loaded.design)
    t0 = time.perf_counter()
    result = run_simulation(loaded.design, design)
    wall = time.perf_counter() - t0
    train = Train(read(scene.path))
    run = Run(scene, train, result, wall)
    run.outcomes = evaluate(scene, train, result)
    return run


def check_ringing(s: Series, train: Train, c: Check) -> tuple[float, str]:
    """Largest standard deviation of F_t over the window, relative to the static force (a settled scene)."""
    def stage(k):
        ft = s.stage(k, "tangential_N")[s.win]
        return (float(np.std(ft)) / abs(train.static_tangential_N(k)),
                f"std F_t {np.std(ft):.3g} N vs static {train.static_tangential_N(k):.6g}")
    return worst_stage(s, stage)


CHECKS["ringing"] = check_ringing


# ------------------------------------------------------------------------------------ the catalogue
# Tolerances shared by many scenes, with their reasons (pitch-line speeds and deflections of the seed).
RATIO_TOL = Check("ratio", 3e-4, "the mean slip over the window is the change of mesh deflection (< 0.1 mm) over "
                  "window x slowest pitch-line speed (0.26 s x 1.76 m/s on the seed's stage-3 pinion): <= 2e-4")
FORCE_TOL = Check("force", 1e-3, "Newton's law holds exactly for the continuous mean; the trapezoid over >= 10 samples "
                  "per period of the ringing leaves < 1e-4 of its amplitude; 10x margin")
ENERGY_TOL = Check("energy_residual", 1e-6, "states at rtol 1e-6 and the work quadratures under error control "
                   "(atol = rtol x energy scale): the balance closes to ~rtol")
NO_NET_WORK_LOST = Check("dissipation", 1e-6, "damping and the tensile clamp only take energy out "
                         "(trapezoid noise of the channel-based balance ~1e-7)", 0.0)


def _scene(name, method, ceiling, *checks, slow=False, energy=True) -> Scene:
    return Scene(name, method, ceiling, tuple(checks) + ((ENERGY_TOL,) if energy else ()), slow)


SCENES: tuple[Scene, ...] = (
    _scene("stiff_linear_100x", "DOP853", 80_000,
           Check("penetration", 1e-3, "linear law: mean penetration = mean F_n / K exactly, and mean F_n is the static "
                 "force up to the momentum term (< 1e-4 here)"), FORCE_TOL, RATIO_TOL),
    _scene("stiff_linear_10000x", "Radau", 1_500,
           Check("penetration", 1e-3, "linear law: mean penetration = F_n / K exactly (no ringing after the ramp)"),
           Check("rigid", 1e-4, "deflections of ~1e-9 m turn the shafts by ~1e-8 rad against ~10 rad: the train is "
                 "rigid, so dKE = J_eff w^2 / 2 and W_load = int T_L w_n dt of the rigid train; trapezoid on the "
                 "smooth STEP products ~1e-7"), RATIO_TOL),
    _scene("stiff_hertz_100x", "DOP853", 120_000,
           Check("penetration", 4e-2, "p ~ F^(2/3) is concave: a ringing of relative std a lowers the mean penetration "
                 "by ~a^2/9 (Jensen; a = 0.41 on stage 1 gives 1.9 %)"), FORCE_TOL, RATIO_TOL),
    _scene("stiff_hertz_10000x", "DOP853", 450_000,
           Check("penetration", 1e-2, "Jensen bias a^2/9 with a = 0.13 (0.2 %) plus the aliased ringing below"),
           Check("force", 3e-3, "the ~3 kHz mesh ringing lies above the 2 kHz Nyquist frequency of 2000 samples in "
                 "0.5 s and aliases into the window mean: <= sqrt(2) std / (pi f_alias T_w) ~ 1e-3"),
           RATIO_TOL, slow=True),
    _scene("light_pinion", "Radau", 5_000,
           Check("input_speed", 1e-9, "T_in i = T_L at every instant (both ramped alike): no net rigid-body torque, "
                 "so the free input shaft keeps its nominal speed; only rounding over ~1e3 steps"),
           Check("static_force", 1e-6, "the 30 kHz pinion mode follows the 0.18 s ramp quasi-statically: no ringing "
                 "to average out"),
           Check("penetration", 1e-6, "quasi-static, as above: mean p = (F_n / K)^(2/3) of the hand calculation"),
           Check("ratio", 1e-9, "no ringing, so no slip; rounding only")),
    _scene("zero_damping", "DOP853", 40_000,
           Check("conservation", 1e-4, "no damping term: W_in - W_load = dKE + dPE; from 20001 samples (~140 per "
                 "period of the 285 Hz run-up mode) the trapezoid of T_in w_in is good to ~1e-5"),
           Check("damping_loss", 0.0, "the law has C = 0: the damping term is absent, its loss exactly 0"),
           FORCE_TOL, RATIO_TOL),
    _scene("heavy_damping", "Radau", 3_000,
           Check("static_force", 1e-3, "C = 5000 N s/mm from 1 um on: 2.6x (stage 3) to 10x (stage 1) critical, no "
                 "ringing; the window mean is the static force up to the overdamped creep"),
           Check("ringing", 1e-3, "overdamped: std of F_t in the window well below 0.1 % of the static force"),
           Check("quasi_static", 5e-3, "overdamped meshes follow the rigid-body run-up force (load plus inertia)"),
           NO_NET_WORK_LOST, RATIO_TOL),
    _scene("damping_depth_tiny", "DOP853", 12_000,
           Check("static_force", 1e-3, "full damping C from 1 um on: 0.1 (stage 1) to 0.03 (stage 3) of critical; the "
                 "run-up ringing has decayed to std/F < 0.05 and averages over ~15 periods of the 58 Hz mode"),
           NO_NET_WORK_LOST, RATIO_TOL),
    _scene("damping_depth_huge", "DOP853", 40_000,
           Check("damping_loss", 1e-6, "at p / d <= 0.1 mm / 10 mm the STEP ramp gives <= 3e-4 of C: the mesh is all "
                 "but undamped (loss measured ~4e-9 of the input work)"),
           Check("conservation", 1e-4, "practically undamped: W_in - W_load = dKE + dPE up to the trapezoid over 2001 "
                 "samples (~14 per period of the 285 Hz mode) and the ~1e-8 loss"),
           FORCE_TOL, RATIO_TOL),
    _scene("overload", "DOP853", 20_000,
           Check("penetration", 1e-3, "1000x the seed load: h0 = (F_n / K)^(2/3) = 100x the seed's "
                 "(1.25/1.83/2.70 mm); ringing std < 1e-3 of F, Jensen bias < 1e-7"),
           Check("warning", 0, "penetration > 10 % of m_n (1.2/1.8/2.5 mm) on every stage must be reported",
                 "more than 10 % of the normal module"),
           FORCE_TOL, RATIO_TOL),
    _scene("rattle_zero_load", "DOP853", 90_000,
           Check("flanks", 0, "no load and no damping: the run-up leaves relative motion that can never settle on one "
                 "flank (contact only pushes), so every mesh crosses the gap and hits both flanks", ("window", "both")),
           Check("conservation", 1e-4, "undamped: W_in = dKE + dPE; 20001 samples put ~80 samples on each ~2 ms "
                 "Hertz impact"),
           Check("force", 1e-3, "Newton's law over the window with the static force 0: only the momentum term "
                 "(tolerance relative to 10 % of the peak force)"),
           Check("ratio", 1e-3, "the deflection wanders across the 0.1 mm gap: mean slip <= 0.3 mm / "
                 "(0.4 s x 1.76 m/s)")),
    _scene("load_reversal", "DOP853", 20_000,
           Check("flanks", 0, "under the reversed load the back flank carries the train once the run-up is over",
                 ("window", "back")),
           Check("flanks", 0, "during the run-up the inertia torque (up to 3x the load) needs the drive flank first",
                 ("run", "both")),
           FORCE_TOL, NO_NET_WORK_LOST, RATIO_TOL),
    _scene("instant_ramps", "DOP853", 40_000,
           Check("force", 1e-3, FORCE_TOL.reason + " (the step load leaves a ringing of ~0.8 F_static)"),
           NO_NET_WORK_LOST, RATIO_TOL),
    _scene("slow_ramps", "DOP853", 50_000,
           Check("quasi_static", 3e-2, "a 2 s ramp against a 58 Hz slowest mode is quasi-static, except that the "
                 "unloaded Hertz mesh has zero stiffness at t = 0: taking up the slack leaves a ringing of a few % of "
                 "the force that the weak damping (~2 N s/mm at 0.01 mm) removes slowly (measured 1.1 %)"),
           Check("static_force", 1e-3, "the ringing has decayed to std/F < 0.5 % by the window"), RATIO_TOL),
    # near auto's line: compiled Radau is predicted cheaper once the kernel is loaded (its load time counts before)
    _scene("long_run", "DOP853|Radau", 180_000,
           Check("static_force", 1e-3, "the 7.8 s window holds ~450 periods of the slowest (58 Hz) mode: the plain "
                 "mean converges like std / (pi N) ~ 2e-5"),
           Check("ratio", 1e-6, "deflection range 1e-3 mm over 7.8 s at 1.76 m/s: slip <= 1e-7"),
           NO_NET_WORK_LOST, FORCE_TOL, slow=True),
    _scene("one_stage", "DOP853", 20_000,
           Check("penetration", 5e-3, "Jensen bias a^2/9 with a = 0.06 (4e-4) plus the momentum term"),
           FORCE_TOL, Check("ratio", 1e-4, "deflection range 2e-3 mm over 0.26 s at the pinion's 7.6 m/s: 1e-6")),
    _scene("five_stages", "Radau", 50_000,
           Check("ratio", 1e-6, "the train settles (std/F < 1e-4): no slip beyond rounding"),
           Check("static_force", 1e-5, "settled: the mean is the static force of every stage"),
           Check("penetration", 1e-5, "settled: h0 = (F_n / K)^(2/3) on every stage")),
    _scene("spur", "DOP853", 20_000,
           Check("axial", 0.0, "beta = 0: F_a = F_t tan 0 is exactly zero"), FORCE_TOL, RATIO_TOL),
    _scene("high_helix", "DOP853", 20_000,
           Check("axial", 1e-12, "F_a = F_t tan 35 deg at every sample (rounding only)"), FORCE_TOL, RATIO_TOL),
    _scene("low_speed", "DOP853", 12_000,
           FORCE_TOL, Check("ratio", 2e-3, "pitch-line speeds 1000x lower (1.8 mm/s at stage 3): deflection range "
                            "1e-3 mm over 0.26 s gives <= 2e-3")),
    _scene("high_speed", "DOP853", 45_000, FORCE_TOL, RATIO_TOL),
    # near auto's line: Radau where the compiled engine is at hand (5e3 evaluations), DOP853 on Python (1.8e4)
    _scene("ratio_1_and_12", "Radau|DOP853", 55_000,
           Check("static_force", 1e-4, "the 400 Hz mode at 2 % of critical rings down to std / F ~ 7e-5 by the window "
                 "(0.18 s on): the mean is the static force up to ~1e-6"), FORCE_TOL,
           Check("ratio", 1e-6, "settled: deflection range ~1e-5 mm over 0.32 s at 2.4 m/s, slip ~1e-8")),
    _scene("crawl_1rpm", "Radau", 20_000,
           Check("static_force", 1e-9, "a 5 s ramp against a 446 Hz mode is quasi-static to ~1e-12 (the mode's "
                 "response to the ramp's jerk, (1 / (2 pi f T))^2 x ...); rtol 1e-10 and rounding only"),
           Check("ringing", 1e-9, "quasi-static: nothing rings (std of F_t at rounding level)"),
           Check("ratio", 1e-9, "no ringing, so no slip; rounding only")),
    _scene("unequal_inertias", "Radau", 20_000,
           FORCE_TOL, Check("ratio", 5e-4, "deflection ranges 0.04/0.06 mm over the 0.8 s window at pitch-line speeds "
                            "0.75/0.38 m/s: <= 2.5e-4")),
)
