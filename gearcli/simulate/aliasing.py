"""Force the output samples cannot resolve: a mode or excitation line above their Nyquist frequency that carries
force in the window (docs/numerics.md, "Aliasing").

The sampling estimate (:mod:`gearcli.simulate.sampling`) interpolates the peaks between samples: it assumes the
force is smooth on the sample grid, each peak sampled a few times. A component above the samples' Nyquist frequency
``fs / 2`` (fewer than 2 samples a period) is not sampled as a peak at all: the samples show it as a slower
sinusoid at its alias ``|f - k fs|`` (folded into 0 .. fs / 2), of the same amplitude (a sinusoid sampled at any
rate keeps its amplitude), so the interpolation sees a smooth signal and its estimate bounds nothing of what lies
between the samples: the window's min, max and std may miss up to about that amplitude.

The candidates are what the scene can put there: its excitation lines (each excitation's fundamental and its first
:data:`gearcli.simulate.sampling.PARTIAL_HARMONICS` harmonics: a transmission error's or stiffness cycle's
harmonics, a torque ripple, a load fluctuation; and its higher harmonics within a mode's resonance band, which a
lightly damped mode amplifies) and its modes' damped frequencies (the run's linearisation) above the Nyquist
frequency. What each carries is measured from the window itself: F_t about its mean projected
on the alias frequency with a Hann window (``2 |sum w x e^(-i w t)| / sum w``: a sinusoid's amplitude, the leakage
of other lines falling as the cube of their distance). It cannot be told apart from a resolved line at the same
alias: an alias within :data:`RESOLUTION_BINS` frequency resolutions ``1 / T`` of an excitation line below the
Nyquist frequency (or of zero: a slow drift) is not judged. A component of more than the sampling target
(:data:`gearcli.simulate.sampling.TARGET`) of the stage's reference force carries force in the window: its sampling
error is not bounded (``sampling_error.aliased``), the stage's min, max and std are unresolved (and its mean, where
the alias's partial periods over the window, ``A |sin(pi n)| / (pi n)`` for ``n`` periods of the alias frequency, exceed
the mean's target: the trapezoid rule integrates the slow alias the samples show, not the fast component; a resonant
mesh sampled once a period gave a window mean of -9705 N where the static force is 9333 N,
tests/simulate/test_aliased_mean.py; and where the samples lock to an excitation's period, :func:`locked_to`, at least
half the force's change over each sample step, averaged over the window, :func:`locked_bias_N`: the samples see
its cycle at the same phases throughout, and its harmonics at multiples of the sample rate fold onto zero, which no
projection measures: a time-varying spur mesh sampled 10 times a period read its mean 3 N off, estimated 0.03 N,
tests/simulate/test_aliased_stage_names_mean.py), and the warning
names the frequency and the ``simulation.steps`` that samples it :data:`~gearcli.simulate.sampling.GOOD_PER_PERIOD`
times a period (where the sampling estimate holds; that run's estimate says what else it needs).
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from gearcli import diagnostics as dg
from gearcli.config.schema import MAX_STEPS
from gearcli.core.jsontypes import JsonObject
from gearcli.diagnostics import Diagnostic
from gearcli.simulate import sampling, stats
from gearcli.simulate.periodic import excitation_periods
from gearcli.simulate.results import SamplingError

RESOLUTION_BINS = 2.0  # the Hann window's main lobe half-width, in units of 1 / T
BAND_WIDTHS = 3.0  # a mode's resonance band whose excitation harmonics are candidates, in half-power half-widths
BAND_MAX = 0.1  # ... at most this share of the mode's frequency either side (a heavily damped mode amplifies little)
MAX_HARMONIC = 256  # the highest harmonic of an excitation taken as a candidate
LOCK_MULTIPLES = (1, 2)  # a lock to an excitation: one of its harmonics within 2 / T of fs or 2 fs (locked_to)


def candidates(layout, eigenvalues: np.ndarray, nyquist_Hz: float,
               span_s: float = 0.0) -> tuple[list[tuple[float, str]], list[float]]:
    """(frequency, label) of the scene's excitation lines and modes above ``nyquist_Hz``, and the excitation lines
    below it (the resolved ones an alias may fall on). Besides each excitation's first harmonics, its higher ones
    within a mode's resonance band above ``nyquist_Hz`` (:data:`BAND_WIDTHS` half-power half-widths sigma / 2 pi,
    at least RESOLUTION_BINS / ``span_s``, at most :data:`BAND_MAX` of its frequency; harmonics up to
    :data:`MAX_HARMONIC`): a lightly damped mode amplifies a high
    harmonic of a stiffness cycle or a contact nonlinearity there."""
    periods = [ex for ex in excitation_periods(layout) if ex.period_s > 0.0]
    modes = [(float(z.imag) / (2.0 * math.pi), max(0.0, -float(z.real)) / (2.0 * math.pi))
             for z in np.asarray(eigenvalues, dtype=complex) if float(z.imag) / (2.0 * math.pi) > nyquist_Hz]
    above: list[tuple[float, str]] = [(f, "natural mode") for f, _ in modes]
    below: list[float] = []
    for ex in periods:
        fe = 1.0 / ex.period_s
        orders = set(range(1, sampling.PARTIAL_HARMONICS + 1))
        for f, half in modes:
            band = min(BAND_MAX * f, max(BAND_WIDTHS * half, RESOLUTION_BINS / span_s if span_s > 0.0 else 0.0))
            orders |= set(range(max(1, math.ceil((f - band) / fe)), min(MAX_HARMONIC, math.floor((f + band) / fe)) + 1))
        for j in sorted(orders):
            if j * fe > nyquist_Hz:
                above.append((j * fe, f"{ex.label} excitation" + (f"'s harmonic {j}" if j > 1 else "")))
            elif j <= sampling.PARTIAL_HARMONICS:
                below.append(j * fe)
    return above, below


def alias_Hz(f: float, fs: float) -> float:
    """Where samples at ``fs`` show a component at ``f``: folded into 0 .. fs / 2."""
    r = math.fmod(f, fs)
    return min(r, fs - r)


def amplitude(t: np.ndarray, centred: np.ndarray, weights: np.ndarray, f: float) -> float:
    """The amplitude of ``centred``'s component at ``f`` (Hann-weighted projection; module text)."""
    phasor = np.exp(-2j * math.pi * f * (t - t[0]))
    return 2.0 * abs(complex(np.sum(weights * centred * phasor))) / float(np.sum(weights))


def mean_bias_N(amplitude_N: float, periods: float) -> float:
    """What a sinusoid of ``amplitude_N`` seen over ``periods`` of its (alias) frequency puts into the window's mean:
    at most A |sin(pi n)| / (pi n), the partial period's (module text)."""
    return amplitude_N * min(1.0, abs(math.sin(math.pi * periods)) / (math.pi * periods)) if periods > 0 else amplitude_N


def found(t: np.ndarray, forces_N: list[np.ndarray], references_N: list[float], steps: int,
          lines: tuple[list[tuple[float, str]], list[float]]) -> list[JsonObject | None]:
    """Per stage (its window F_t in ``forces_N``), the strongest component of ``lines`` above the Nyquist frequency
    of the window's samples ``t`` that carries more than the target of its reference force (module text), or None:
    {frequency_Hz, source, alias_Hz, amplitude_N, samples_per_period, steps} (``steps``: the file's
    ``simulation.steps`` that samples it GOOD_PER_PERIOD times a period; None beyond the schema's maximum). Each
    alias's phasor is made once, for every stage."""
    above, below = lines
    n, span = t.size, float(t[-1] - t[0]) if t.size > 1 else 0.0
    best: list[JsonObject | None] = [None] * len(forces_N)
    judged = [k for k, ref in enumerate(references_N) if ref > 0.0]
    if not above or not judged or n < sampling.MIN_WINDOW_SAMPLES or not span > 0.0:
        return best
    fs, gap = (n - 1) / span, RESOLUTION_BINS / span
    weights = 0.5 - 0.5 * np.cos(2.0 * math.pi * (t - t[0]) / span)
    total = float(np.sum(weights))
    # every judged stage's Hann-weighted F_t about its weighted mean, one row each (einsum: no BLAS threads)
    rows = np.array([weights * (forces_N[k] - float(np.einsum("i,i->", weights, forces_N[k])) / total)
                     for k in judged])
    for f, label in above:
        fa = alias_Hz(f, fs)
        if fa < gap or any(abs(fa - g) < gap for g in below):
            continue  # a drift, or a resolved line's: the projection cannot tell them apart
        phase = (2.0 * math.pi * fa) * (t - t[0])
        amps = 2.0 * np.hypot(np.einsum("kn,n->k", rows, np.cos(phase)), np.einsum("kn,n->k", rows, np.sin(phase))) \
            / total
        for k, a in zip(judged, (float(x) for x in amps), strict=True):
            if a > sampling.TARGET * references_N[k] and (best[k] is None or a > _num(best[k] or {}, "amplitude_N")):
                want = sampling.up_to_two_figures(steps * sampling.GOOD_PER_PERIOD * f / fs, slack=1e-9)
                best[k] = {"frequency_Hz": f, "source": label, "alias_Hz": fa, "amplitude_N": a,
                           "samples_per_period": fs / f, "steps": want if want <= MAX_STEPS else None,
                           "mean_bias_N": mean_bias_N(a, fa * span)}
    return best


def window_sampling(t: np.ndarray, mask: np.ndarray, per_stage: list, spec, solver_errors: list,
                    steps: int | None, periodic: bool, window_share: float, floors: list[float],
                    reduced: stats.Reduced | None = None, layout=None, eigenvalues: np.ndarray | None = None,
                    planets: dict | None = None, planet_reduced: dict | None = None) -> list[SamplingError | None]:
    """Per stage, the output sampling's error of the window min and max of F_t (:mod:`gearcli.simulate.sampling`),
    judged with the solver's estimate where a check pass ran, and a fixed window's force above the samples' Nyquist
    frequency (``layout``, ``eigenvalues``: the scene's excitations and modes, read for a fixed window only; module
    text); None for an empty window. ``reduced``: the window's reductions (:func:`gearcli.simulate.stats.window_reductions`).
    ``planets``: (stage, planet, "sun" | "ring") -> (F_t, ...) of every planet mesh
    (:func:`gearcli.simulate.planet_stats.planet_series`): a planetary stage's estimate is its worst planet mesh's;
    ``planet_reduced``: their windows' reductions (:func:`gearcli.simulate.stats.planet_windows`)."""
    sel = stats.window_slice(mask) if reduced is None else reduced.sel  # the reductions' window: the same slice
    tw = t[sel]
    if tw.size == 0:
        return [None] * len(spec.meshes)
    basis = int(tw.size) if periodic or steps is None else int(steps)  # whole periods: steps per window
    dt = np.diff(tw)  # the window's steps, every stage's
    out: list[SamplingError | None] = [
        sampling.stage_sampling(tw, np.asarray(per_stage[k][0])[sel], m.static_tangential_N, basis, periodic=periodic,
                                solver=solver_errors[k], window_share=window_share, floor_N=floors[k], dt=dt,
                                reduced=None if reduced is None else reduced.force(k))
        for k, m in enumerate(spec.meshes)]
    for key, series in (planets or {}).items():  # every planet's sun and ring mesh prints its min and max too
        k, se = key[0], out[key[0]]
        if se is not None and not sampling.too_few(se):
            other = sampling.stage_sampling(tw, np.asarray(series[0])[sel], spec.meshes[k].static_tangential_N, basis,
                                            periodic=periodic, solver=solver_errors[k], window_share=window_share,
                                            floor_N=floors[k], dt=dt,
                                            reduced=None if planet_reduced is None else planet_reduced[key][1])
            out[k] = worse(se, other)
    if periodic or layout is None or tw.size < sampling.MIN_WINDOW_SAMPLES or not float(tw[-1] - tw[0]) > 0.0:
        return out  # a periodic window: 64 samples a period of its fastest excitation
    forces = [np.asarray(per_stage[k][0])[sel] for k in range(len(out))]
    lock = locked_to(layout, tw)
    biases = [locked_bias_N(tw, f) for f in forces] if lock is not None else []  # each stage's, once for both uses
    if lock is not None:  # the samples' own estimate of a locked stage's unresolved mean understates it (module text)
        out = [se if se is None or sampling.too_few(se) else locked_mean(se, biases[k]) for k, se in enumerate(out)]
    nyquist = 0.5 * (tw.size - 1) / float(tw[-1] - tw[0])
    lines = candidates(layout, np.zeros(0) if eigenvalues is None else eigenvalues, nyquist, float(tw[-1] - tw[0]))
    judged = [se is not None and not sampling.too_few(se) for se in out]
    hits = found(tw, forces,
                 [se.reference_N if se is not None and ok else 0.0 for se, ok in zip(out, judged, strict=True)],
                 basis, lines)
    if lock is not None:  # the samples sit at the same phases of that cycle: its folded harmonics bias the mean
        hits = [hit if hit is None else {**hit, "locked_to": lock,
                                         "mean_bias_N": max(_num(hit, "mean_bias_N"), biases[k])}
                for k, hit in enumerate(hits)]
    return [se if se is None else unbounded(se, hit) for se, hit in zip(out, hits, strict=True)]


def locked_to(layout, t: np.ndarray) -> str | None:
    """The excitation whose period the samples ``t`` lock to (module text), or None: one whose harmonic nearest
    to the sample rate ``fs`` (or to ``2 fs``; at most :data:`MAX_HARMONIC`, more than 2 samples a period) lies
    within :data:`RESOLUTION_BINS` frequency resolutions ``1 / T`` of it, the excitation faster than 4 of them.
    Its harmonics at multiples of ``fs`` fold onto zero, so the samples see its cycle at the same few phases
    throughout the window and their mean is that of those phases, not the cycle's."""
    span = float(t[-1] - t[0])
    fs, gap = (t.size - 1) / span, RESOLUTION_BINS / span
    for ex in excitation_periods(layout):
        fe = 1.0 / ex.period_s if ex.period_s > 0.0 else 0.0
        if fe > 4.0 * gap:  # a slower one always has a harmonic within fe / 2 of fs: no coincidence, no lock
            for m in LOCK_MULTIPLES:
                j = round(m * fs / fe)
                if 2 * m < j <= MAX_HARMONIC and abs(j * fe - m * fs) < gap:  # under 2 samples a period: found's
                    return ex.label
    return None


def locked_bias_N(t: np.ndarray, force_N: np.ndarray) -> float:
    """What the samples' lock to a cycle (:func:`locked_to`) may put into the trapezoid rule's window mean of
    ``force_N``: half the force's change over each sample step, averaged over the window. The samples see the
    cycle at fixed phases, so what lies between two of them (a step of the force where the tooth pairs in
    contact change, the ringing after it) is never averaged out; where the force runs monotonic between two
    samples, the trapezoid's error over the step is at most half its change times the step."""
    span = float(t[-1] - t[0])
    return float(np.einsum("i,i->", np.abs(np.diff(force_N)), np.diff(t))) / (2.0 * span) if span > 0.0 else 0.0


def locked_mean(se: SamplingError, bound_N: float) -> SamplingError:
    """``se`` with its mean's error the lock's bound ``bound_N`` (:func:`locked_bias_N`) where that is larger and
    the samples' own estimate (Richardson's, which every other sample, locked too, cannot see past) already leaves
    the mean unresolved; its suggestion kept (the bound, pessimistic for samples that do not lock, would ask for
    more than the schema allows); a resolved mean is kept (locked samples integrate a smooth force well). tr29a: 1999 steps over 0.1 s of a
    time-varying spur mesh at 2 kHz (9.995 samples a period) read 39.01 N against 41.67 N, estimated 0.097 N."""
    if se.relative["mean"] <= sampling.MEAN_TARGET or not bound_N > se.mean_N or se.reference_N <= 0.0:
        return se
    return replace(se, mean_N=bound_N, relative={**se.relative, "mean": bound_N / se.reference_N})


def worse(a: SamplingError, b: SamplingError) -> SamplingError:
    """``a`` (a planetary stage's planet-1 estimate) with each error the larger of its and ``b``'s (another planet
    mesh's), over ``a``'s reference force; unresolved where either is, suggesting the larger number of steps."""
    err = {"min": max(a.min_N, b.min_N), "max": max(a.max_N, b.max_N), "mean": max(a.mean_N, b.mean_N),
           "std": max(a.std_N, b.std_N)}
    rel = {q: (v / a.reference_N if a.reference_N > 0 else max(a.relative[q], b.relative[q])) for q, v in err.items()}
    steps = [x.suggested_steps for x in (a, b) if not x.resolved]
    return replace(a, min_N=err["min"], max_N=err["max"], mean_N=err["mean"], std_N=err["std"], relative=rel,
                   resolved=a.resolved and b.resolved,
                   suggested_steps=None if not steps or None in steps else max(x for x in steps if x is not None))


def unbounded(se: SamplingError, alias: JsonObject | None) -> SamplingError:
    """``se`` with the component ``alias`` (:func:`found`) that the samples cannot resolve: not resolved, its
    suggestion the steps that sample it (kept where the estimate's own asks for more)."""
    if alias is None:
        return se
    want = alias["steps"]
    steps = want if isinstance(want, int) and (se.suggested_steps is None or se.resolved
                                               or want > se.suggested_steps) else se.suggested_steps
    bias = max(se.mean_N, _num(alias, "mean_bias_N"))  # the samples' mean follows the alias (module text)
    return replace(se, resolved=False, suggested_steps=steps, aliased=alias, mean_N=bias,
                   relative={**se.relative, "mean": bias / se.reference_N if se.reference_N > 0 else 0.0})


def _unbounded_statistics(s: SamplingError) -> list[str]:
    """What the alias leaves unknown: min, max and std, and the mean where its partial periods, or the samples' own
    estimate of the mean (``mean_N``: the larger of the two, :func:`unbounded`), exceed the mean's target. The
    alias's warning stands in for :func:`gearcli.simulate.sampling.warnings`' of the stage, so it names every
    statistic the samples leave unresolved: a time-varying spur mesh at 10,000 rpm sampled 10 times a mesh period
    kept its mean (44.7 N, static 41.67 N) unresolved in ``error_estimate.unresolved`` while its warning named
    min, max and std only (tests/simulate/test_aliased_stage_names_mean.py)."""
    biased = s.aliased is not None and max(s.mean_N, _num(s.aliased, "mean_bias_N")) > \
        sampling.MEAN_TARGET * s.reference_N
    return ["mean", *sampling.UNBOUNDED] if biased else list(sampling.UNBOUNDED)


def _mean_words(s: SamplingError, a: JsonObject) -> str:
    """The warning's words on the mean: the alias's partial-period bias where that is the larger estimate, else the
    samples' own (Richardson's, :func:`gearcli.simulate.sampled_moments.mean_error`)."""
    bias = _num(a, "mean_bias_N")
    if bias >= s.mean_N and a.get("locked_to"):
        return (f" (and the mean, by up to {bias:.3g} N: the samples lock to the {a['locked_to']}'s period, "
                "seeing it at the same phases throughout, its harmonics above the Nyquist frequency folded onto "
                "zero)")
    if bias >= s.mean_N:
        return f" (and the mean, which the samples take from the slow alias, by up to {bias:.3g} N)"
    return (f" (and the mean: the integral over the samples is estimated {s.mean_N:.3g} N off, a third of its change "
            "when every other sample is left out, the force's steps or harmonics folded onto the samples)")


def warnings(samplings: list[SamplingError | None]) -> list[Diagnostic]:
    """``statistics_undersampled``, one per stage whose window carries force above the samples' Nyquist frequency
    (module text; the other stages' are :func:`gearcli.simulate.sampling.warnings`')."""
    out = []
    for k, s in enumerate(samplings):
        a = s.aliased if s is not None else None
        if s is None or a is None or sampling.too_few(s):
            continue
        named = _unbounded_statistics(s)
        mean = _mean_words(s, a) if "mean" in named else ""
        out.append(dg.warning(
            dg.STATISTICS_UNDERSAMPLED,
            f"stage {k + 1}: F_t {', '.join(named)} not resolved by the output samples, and no estimate "
            f"from them bounds the error: {_carried(a)}, so what lies between them may reach that amplitude{mean}; "
            f"{_fix(a, 'it')}",
            stage=k + 1, statistics=named, estimated_error_N=None, relative_error=None,
            steps=a["steps"], steps_cap=s.steps_cap, aliased_Hz=a["frequency_Hz"], amplitude_N=a["amplitude_N"]))
    return out


def peak_warnings(found: list[Diagnostic], samplings: list[SamplingError | None], t: np.ndarray,
                  forces_N: list[np.ndarray], steps: int = 1, fastest_Hz: float = 0.0) -> list[Diagnostic]:
    """``found`` (:func:`gearcli.simulate.sampling.peak_warnings`) with the run's peak of every stage whose window
    carries force above the samples' Nyquist frequency, more than the target of that peak, warned as not bounded
    by them (the whole run's F_t ``forces_N`` at the times ``t``; the frequency's suggestion), in place of its
    estimate's warning. A run of fewer than 3 samples (``simulation.steps = 1``, ``steps``), which gives the
    estimate no sample between its ends, has every loaded stage's peak warned as not bounded, the suggestion
    sampling the scene's fastest natural frequency ``fastest_Hz`` as an aliased peak's does."""
    if t.size < 3:
        return [_bare_peak_warning(k, np.abs(np.asarray(f, dtype=float)), t, steps, fastest_Hz)
                for k, f in enumerate(forces_N) if np.size(f) and float(np.max(np.abs(f))) > 0.0]
    aliased = {k: s.aliased for k, s in enumerate(samplings) if s is not None and s.aliased is not None}
    if not aliased:
        return found
    peaks = {k: np.abs(np.asarray(forces_N[k], dtype=float)) for k in aliased if k < len(forces_N)}
    over = {k: int(np.argmax(f)) for k, f in peaks.items()
            if f.size and _num(aliased[k], "amplitude_N") > sampling.TARGET * float(np.max(f))}
    out = [d for d in found if _stage(d) - 1 not in over]
    for k, i in over.items():
        a, peak = aliased[k], float(peaks[k][i])
        out.append(dg.warning(
            dg.PEAK_UNDERSAMPLED,
            f"stage {k + 1}: the run's peak |F_t| {peak:.5g} N (at {float(t[i]):.3g} s) and its run-up factor are not "
            f"resolved by the output samples, and no estimate from them bounds the error: {_carried(a)}; "
            f"{_fix(a, 'it')}",
            stage=k + 1, peak_N=peak, estimated_error_N=None, relative_error=None, steps=a["steps"],
            steps_cap=MAX_STEPS, aliased=True, aliased_Hz=a["frequency_Hz"]))
    return sorted(out, key=_stage)


def _bare_peak_warning(k: int, a: np.ndarray, t: np.ndarray, steps: int, fastest_Hz: float) -> Diagnostic:
    """``peak_undersampled`` of a stage whose run has no sample between its ends: its peak |F_t| is one of its
    end samples', and the run-up's peak between them is not seen (a run from rest at t = 0, at rest)."""
    i, span = int(np.argmax(a)), float(t[-1] - t[0])
    want = sampling.up_to_two_figures(max(2.0 * steps, span * fastest_Hz * sampling.GOOD_PER_PERIOD))
    n = want if fastest_Hz > 0.0 and span > 0.0 and want <= MAX_STEPS else None
    fix = (f"--set simulation.steps={n} samples the scene's fastest natural frequency {sampling.GOOD_PER_PERIOD:g} "
           "times a period" if n is not None else "more output samples (simulation.steps) show it")
    return dg.warning(
        dg.PEAK_UNDERSAMPLED,
        f"stage {k + 1}: the run's peak |F_t| {float(a[i]):.5g} N (at {float(t[i]):.3g} s) and its run-up factor are "
        f"not resolved by the output samples, and no estimate from them bounds the error: the run has {t.size} "
        f"samples, none between its ends, so they do not see the run-up's peak; {fix}",
        stage=k + 1, peak_N=float(a[i]), estimated_error_N=None, relative_error=None, steps=n, steps_cap=MAX_STEPS,
        aliased=False)


def _carried(a: JsonObject) -> str:
    return (f"the {a['source']} at {_num(a, 'frequency_Hz'):.4g} Hz carries ±{_num(a, 'amplitude_N'):.3g} N in the "
            f"window and is sampled {_num(a, 'samples_per_period'):.2g} times a period (fewer than 2: the samples "
            f"show it at {_num(a, 'alias_Hz'):.4g} Hz)")


def _num(a: JsonObject, key: str) -> float:
    value = a.get(key)
    return float(value) if isinstance(value, (int, float)) else math.nan


def _stage(d: Diagnostic) -> int:
    stage = d.data.get("stage")
    return stage if isinstance(stage, int) else 0


def _fix(a: JsonObject, what: str) -> str:
    if a.get("steps") is not None:
        return f"--set simulation.steps={a['steps']} samples {what} {sampling.GOOD_PER_PERIOD:g} times a period"
    return (f"the schema's maximum simulation.steps = {MAX_STEPS} cannot sample {what}: a shorter run "
            "(simulation.duration_s)")
