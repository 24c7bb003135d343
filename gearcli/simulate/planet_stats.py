"""A planetary stage's planets over the statistics window: every planet mesh's F_t and DTE statistics, the
load-sharing factor, and the stage's dynamic and run-up factors taken at its most loaded planet."""

from __future__ import annotations

from dataclasses import replace
from typing import TYPE_CHECKING, Any

import numpy as np

from gearcli import diagnostics as dg
from gearcli.model.outputs import tooth_forces
from gearcli.simulate import stats

if TYPE_CHECKING:
    from gearcli.diagnostics import Diagnostic
    from gearcli.model import TorsionalModel
    from gearcli.model.outputs import Sampled
    from gearcli.simulate.planet_results import PlanetDynamics
    from gearcli.simulate.results import StageDynamics


#: a stage whose planets' mean sun-mesh force is below this fraction of the run's peak carries no load to share
UNLOADED_OF_PEAK = 1e-3


def planet_series(model: TorsionalModel, s: Sampled) -> dict[tuple[int, int, str], tuple[np.ndarray, np.ndarray]]:
    """(stage, planet, "sun" | "ring") -> (F_t in N, DTE in m) of every planet mesh, in connector order."""
    lay = model.layout
    out: dict = {}
    for c, x in enumerate(lay.connectors):
        if x.load_body >= 0:
            ft = tooth_forces(lay, x.index, s.connectors[c].line_force_N)[0]
            out[(x.index, x.planet, x.gear)] = (ft, s.connectors[c].dte_m)
    return out


def planet_contact_warnings(model: TorsionalModel, s: Sampled, mask: np.ndarray, flank: float = 1.0) -> list[Diagnostic]:
    """The contact-loss warning of every planet mesh (each planet's sun and ring mesh) whose loaded flank loses
    contact in the steady window, the planet named: a stage's channel is planet 1's sun mesh alone, and a position
    error can leave any planet inside the backlash, carrying nothing while the others take its share. The loaded
    flank is the stage's (both meshes of every planet are signed as its sun's torque: docs/output.md)."""
    lay, out = model.layout, []
    sel = stats.window_slice(mask)
    for c, x in enumerate(lay.connectors):
        if x.load_body < 0:  # not a planet mesh
            continue
        m = lay.spec.meshes[x.index]
        pen = s.connectors[c].penetration_m[sel]
        loaded = flank * (1.0 if m.static_tangential_N >= 0 else -1.0)  # flank: gearcli.simulate.stats.loaded_flank
        lost = loaded * pen <= 0.0
        if m.static_tangential_N == 0 or not pen.size or not np.any(lost):
            continue
        where = f"stage {x.index + 1} planet {x.planet + 1} {x.gear} mesh"
        if np.all(loaded * pen < 0.0):  # held on its back flank: a position error, no vibration, does that
            words = ("presses its back flank throughout the steady window: the planet is loaded backwards and the "
                     "others carry more than the whole load (a planet.position_error_um beyond the loaded planets' "
                     "mesh deflection and the backlash)")
        elif np.all(lost):
            words = ("never touches its loaded flank in the steady window: the planet carries no load and the other "
                     "planets carry its share (a planet.position_error_um larger than the loaded planets' mesh "
                     "deflection leaves it inside the backlash)")
        else:
            words = stats.contact_loss_words(loaded, m, lost)
        out.append(dg.warning(dg.CONTACT_LOSS, f"{where}: {words}", stage=x.index + 1, planet=x.planet + 1,
                              mesh="sun_planet" if x.gear == "sun" else "planet_ring", fraction=float(lost.mean())))
    return out


def peak_series(model: TorsionalModel, s: Sampled, stages_ft: list[np.ndarray]) -> list[np.ndarray]:
    """Each stage's F_t whose whole-run peak is the stage's ``peak_tangential_N``: ``stages_ft`` (the stages'
    channels), a planetary stage's replaced by its most loaded planet's sun mesh (:func:`with_planets`), so that the
    peak's sampling estimate reads the series the peak comes from."""
    out = list(stages_ft)
    suns: dict[int, list[np.ndarray]] = {}
    for (k, _, gear), (ft, _) in planet_series(model, s).items():
        if gear == "sun":
            suns.setdefault(k, []).append(ft)
    for k, fs in suns.items():
        if k < len(out) and fs:
            out[k] = max(fs, key=lambda f: float(np.max(np.abs(f))) if f.size else 0.0)
    return out


def planets_of(model: TorsionalModel, s: Sampled, mask: np.ndarray, k: int, periodic: bool = False,
               every: dict[tuple[int, int, str], tuple[np.ndarray, np.ndarray]] | None = None,
               windows: dict[tuple[int, int, str], tuple[Any, tuple]] | None = None
               ) -> tuple[tuple[PlanetDynamics, ...], float | None, tuple[float, float]]:
    """Stage k's planets over the window, the load-sharing factor (largest window-mean |F_t| of the sun meshes over
    the mean planet's, the sun torque's share: |mean of the flank-signed means|; None for a parallel stage and for
    an unloaded one) and the whole run's peak |F_t| over every planet's sun mesh with its time (0, 0 for a parallel
    stage). ``every``, ``windows``: :func:`planet_series` of ``model`` and ``s`` and
    :func:`gearcli.simulate.stats.planet_windows` of its meshes over ``mask``, where the caller has them (made once
    for every stage)."""
    every = planet_series(model, s) if every is None else every
    series = {key[1:]: v for key, v in every.items() if key[0] == k}
    if not series:
        return (), None, (0.0, 0.0)
    from gearcli.simulate.planet_results import PlanetDynamics  # lazy: a planetary stage only

    windows = stats.planet_windows(s.time_s, mask, every, periodic, k) if windows is None else windows
    n = 1 + max(j for j, _ in series)
    planets = tuple(PlanetDynamics(j + 1, windows[(k, j, "sun")][0], windows[(k, j, "ring")][0]) for j in range(n))
    # signed by the flank: a planet that a position error pushes onto its back flank takes load off the others, so
    # the mean planet is the sun torque's share, |mean of the signed means| (a mean of magnitudes counted it twice)
    signed = np.array([p.sun.tangential_N.mean for p in planets])
    means, share = np.abs(signed), abs(float(signed.mean()))
    suns = np.abs(np.stack([series[(j, "sun")][0] for j in range(n)]))  # each sun mesh's |F_t| over the run
    peaks = list(zip(suns.max(axis=1).tolist(), suns.argmax(axis=1).tolist(), strict=True))
    peak, at = max(peaks)
    # an unloaded stage's window means are round-off (~1e-10 N): their ratio is no load sharing (the report's
    # accuracy study takes the same line between a load and none: 1e-3 of the run-up peak)
    loaded = share > UNLOADED_OF_PEAK * peak
    return planets, (float(means.max() / share) if loaded else None), (peak, float(s.time_s[at]))


def with_planets(st: StageDynamics, planets: tuple[PlanetDynamics, ...], sharing: float | None,
                  worst: tuple[float, float]) -> StageDynamics:
    """A planetary stage's planets, and its dynamic and run-up factors (and run peak) those of its most loaded
    planet's sun mesh, as its simulated K_v (:func:`gearcli.rating.dynamic.stage_simulated_k_v`): planet 1's
    channels (the stage's ``tangential_N``) alone miss a planet that unequal spacing, position errors or
    phasing load more."""
    if not planets:
        return st
    ref = st.simulated_static_tangential_N
    changes: dict = {"planets": planets, "load_sharing_factor": sharing}
    window_max = max(max(abs(p.sun.tangential_N.max), abs(p.sun.tangential_N.min)) for p in planets)
    if st.dynamic_factor is not None and ref:
        changes["dynamic_factor"] = max(st.dynamic_factor, window_max / abs(ref))
    peak, at = worst
    if peak > st.peak_tangential_N:
        changes.update(peak_tangential_N=peak, peak_time_s=at,
                       runup_factor=peak / abs(ref) if ref else st.runup_factor)
    return replace(st, **changes)
