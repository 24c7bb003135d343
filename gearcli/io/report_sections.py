"""A report as titled sections of text cells, shared by the rich-table and the markdown writers.

Each section is a table (headers, rows of strings, column alignment) with notes under it; the two
writers only differ in how they draw it. Errors below the reference's resolution are shown as
``< u`` (u the reference's resolution of that quantity, its difference from the check run), never as a number that would suggest a precision the study
cannot resolve.
"""

from __future__ import annotations

import math

from gearcli import diagnostics as dg
from gearcli.core.records import record
from gearcli.core.text import figure, rounded_up, shorten
from gearcli.io.table_kit import spread_digits
from gearcli.io.units import of_result
from gearcli.model.modes import RESONANCE_BAND, near_nominal
from gearcli.report.compare import reversed_lossy_stages
from gearcli.report.result import AccuracyRun, AccuracyStudy, ReferenceRun, Report
from gearcli.simulate.estimate import reference_words

LABELS = {
    "ratio": "ratio i",
    "input_speed_deg_s": "input speed [°/s]",
    "output_speed_deg_s": "output speed [°/s]",
    "tangential_N": "F_t mean [N]",
    "radial_N": "F_r mean [N]",
    "axial_N": "F_a mean [N]",
}
STAGE_LABELS = {"output_speed_deg_s": "stage output speed [°/s]", "ratio": "stage ratio"}


@record
class Section:
    title: str
    headers: tuple[str, ...]
    rows: tuple[tuple[str, ...], ...]
    align: str  # one "l" or "r" per column
    notes: tuple[str, ...] = ()


def g(v: float | None, digits: int = 5) -> str:
    return "–" if v is None else f"{v + 0.0:.{digits}g}"  # + 0.0: no negative zero


def bound_text(bound: float, digits: int, kind: str = "g") -> str:
    """The bound e of a ``< e`` cell to ``digits`` significant digits, rounded up (:func:`rounded_up`): a figure
    below e printed as ``< e`` must stay below the printed number (an error of 1.44 % under an estimate of 1.455 %
    is ``< 2``, not ``< 1``)."""
    return f"{rounded_up(bound, digits):.{digits - 1 if kind == 'e' else digits}{kind}}"


def percent(v: float | None) -> str:
    return "–" if v is None else f"{v:+.3g}"


def quantity_label(stage: int | None, quantity: str) -> str:
    if stage is not None and quantity in STAGE_LABELS:
        return STAGE_LABELS[quantity]
    return LABELS.get(quantity, quantity)


def _in_units(r: Report, quantity: str, label: str, theory: float, simulated: float) -> list[tuple[str, float, float]]:
    """A comparison row as the table prints it: a speed row (kept in °/s) in each of the design file's table units
    (its own, and rpm beside °/s or rad/s: docs/output.md, "Units"), any other row as it is."""
    if not quantity.endswith("_deg_s"):
        return [(label, theory, simulated)]
    return [(label.replace("[°/s]", f"[{unit}]"), f(theory), f(simulated))
            for unit, f in of_result(r.simulation).table_speeds()]


def comparison_section(r: Report) -> Section:
    rows = []
    reversed_stages = reversed_lossy_stages(r.design)
    mean_errors = _mean_force_errors_percent(r)
    unresolved = False
    for row in r.comparison:
        bound = mean_errors.get(row.stage) if row.stage is not None and row.quantity in FORCE_QUANTITIES else None
        below = bound is not None and row.error_percent is not None and abs(row.error_percent) < bound
        unresolved |= below
        for label, theory, simulated in _in_units(r, row.quantity, quantity_label(row.stage, row.quantity),
                                                  row.theory, row.simulated):
            rows.append(("train" if row.stage is None else str(row.stage), label, g(theory, 6), g(simulated, 6),
                         f"< {bound_text(bound, 1)}" if below and bound is not None else percent(row.error_percent)))
    notes = ("'< e' (forces): the difference is below e, the run's estimated error of its window mean (check pass "
             "and sampling), so the simulated mean meets the theory to within its own accuracy",) if unresolved else ()
    w0, w1 = r.simulation.window_s
    return Section("Theory against simulation", ("stage", "quantity", "theory (static)", "simulated (mean)",
                                                 "error [%]"), tuple(rows), "llrrr",
                   (f"simulated: mean over the steady window {w0:.4g}–{w1:.4g} s; error = (simulated − theory)"
                    " / |theory|" + ("; a planetary stage's forces: the mean over its planets' sun meshes (each planet's"
                                     " own: gearcli simulate, JSON planets)" if _has_planets(r) else "")
                    + ("; reversed load (the gear drives) on stage " + ", ".join(map(str, reversed_stages))
                       + ": theory's forces are the driving gear's, T_g / r_g = the design's F_t / η"
                       if reversed_stages else ""), *notes, *_theory_point_note(r)))


def _theory_point_note(r: Report) -> tuple[str, ...]:
    """Where the theory is taken, when not at the design's nominal speed (:class:`TheoryPoint`)."""
    p = r.theory_point
    drive = tuple(f"warning: {d.message}" for d in r.diagnostics if d.code in DRIVE_STATE_CODES)
    if p is None:
        return drive
    if not p.reached:
        why = ("the motor's steady curve carries the load at no speed from rest (it cannot start, falls out of its "
               "start, or nothing holds it: it runs away)" if p.drive == "motor" else
               "the torque drive's torque meets the load at no speed, so the train accelerates or decelerates "
               "for the whole run")
        return (f"NO steady operating point: {why}. The theory column is the design's nominal point, which the run "
                "never reaches, and the simulated means are a transient's over the window: no speed or force error "
                "is given (only the ratios, kinematics, are compared)", *drive)
    u = of_result(r.simulation)
    unit, at, nominal = u.speed_label, u.speed_from_deg_s(p.input_speed_deg_s), u.speed_from_deg_s(
        p.nominal_input_speed_deg_s)
    where = ("the motor's operating point (its curve crossing the load reflected to it, losses included)"
             if p.drive == "motor" else "the torque drive's balance with the speed-dependent load")
    return (f"theory at {where}: input {at:.6g} {unit} (the design's nominal {nominal:.6g} {unit}), the speeds scaled "
            f"to it" + (f", the forces at the load there, {p.load_factor:.6g}x the nominal torque"
                        if p.load_factor != 1.0 else ""), *drive)


#: the run's warnings on where its drive settles, repeated under the comparison (whose theory they qualify)
DRIVE_STATE_CODES = (dg.MOTOR_STALLS, dg.MOTOR_RUNS_AWAY, dg.MOTOR_ROLLS_BACK, dg.START_NOT_SETTLED,
                     dg.WINDOW_NOT_SETTLED)


FORCE_QUANTITIES = ("tangential_N", "radial_N", "axial_N")


def _mean_force_errors_percent(r: Report) -> dict[int, float]:
    """Per stage, the estimated error of the window mean F_t in percent of it (the check pass's and the sampling's
    together; F_r and F_a share it, being F_t times constants): a theory-simulation difference below it is not
    resolved by the run, and its digits ("+5.04e-07") would be the solver's noise."""
    out = {}
    for st in r.simulation.stages:
        e = st.error_estimate
        if e is None:
            continue
        rel = e.total_relative.get("mean", e.relative.get("mean"))
        if rel is not None and math.isfinite(rel) and rel > 0:
            out[st.index] = 100.0 * rel
    return out


def _has_planets(r: Report) -> bool:
    return any(getattr(s, "planets", ()) for s in r.simulation.stages)


def fluctuation_section(r: Report) -> Section:
    rows = []
    for s in r.stages:
        for name, st in (("F_t [N]", s.tangential_N), ("F_r [N]", s.radial_N), ("F_a [N]", s.axial_N)):
            rows.append((str(s.stage) if name.startswith("F_t") else "", name, g(st.mean), g(st.std, spread_digits(st.std, st.mean)),
                         g(st.min), g(st.max)))
    return Section("Mesh force fluctuation over the steady window", ("stage", "force", "mean", "std", "min", "max"),
                   tuple(rows), "llrrrr")


def peaks_section(r: Report) -> Section:
    rows = tuple((str(s.stage), g(s.static_tangential_N if s.simulated_static_tangential_N is None
                                  else s.simulated_static_tangential_N),
                  g(max(abs(s.tangential_N.max), abs(s.tangential_N.min))),
                  g(s.dynamic_factor, 4),
                  g(s.peak_tangential_N), g(s.peak_time_s, 3), g(s.runup_factor, 4)) for s in r.stages)
    return Section("Dynamic factor and run-up peak", ("stage", "static F_t as simulated [N]", "window max |F_t| [N]",
                                                      "dynamic factor", "run peak |F_t| [N]", "at t [s]",
                                                      "run-up factor"), rows, "lrrrrrr",
                   ("dynamic factor = max |F_t| over the steady window / |static F_t| of the simulated load (the "
                    "stage efficiencies act in the dynamics, so it equals the design's static F_t; with a reversed load the "
                    "driving gear's, the design's over η); "
                    "run-up factor = peak |F_t| over the whole run, run-up included / |static F_t|",
                    *sampling_notes(r)))


def sampling_notes(r: Report) -> list[str]:
    """The output sampling's error of each stage's window min and max of F_t (every run: the peaks between the
    samples, docs/numerics.md "Honest statistics"), and the steps that resolve an unresolved one."""
    out = []
    for st in r.simulation.stages:
        e = st.sampling_error
        if e is None:
            continue
        fix = "" if e.resolved else (f" — NOT resolved: --set simulation.steps={e.suggested_steps}"
                                     if e.suggested_steps else " — NOT resolved within the schema's maximum steps")
        if e.aliased:  # force above the samples' Nyquist frequency: no bound (gearcli.simulate.aliasing)
            out.append(f"stage {st.index}: sampling error of the window min / max F_t not bounded: the "
                       f"{e.aliased.get('source')} at {e.aliased.get('frequency_Hz'):.4g} Hz is above the samples' "
                       f"Nyquist frequency{fix}")
            continue
        out.append(f"stage {st.index}: sampling error of the window min / max F_t {e.min_N:.2g} / {e.max_N:.2g} N "
                   f"({e.relative['min']:.1e} / {e.relative['max']:.1e} of "
                   f"{reference_words(e.reference_N, True) if not st.static_tangential_N else 'the mean'}, target "
                   f"{e.target_relative:g}; "
                   f"{e.samples} window samples){fix}")
    return out


def peak_text(peak_Hz: float, resolution_Hz: float, whole_periods: bool = False) -> str:
    """"f ± 1/T" with f printed to the decimal place of the resolution's second digit, no further: a bin's
    centre is good to the resolution, so "0.6248 ± 0.62" claimed digits the FFT cannot give ("0.62 ± 0.62").
    ``whole_periods``: the window is whole periods of a repeating response, whose every line is a harmonic k/T of its
    period and so lies on a bin exactly: f itself, without a ± (a one-period window of a 490 Hz orbit printed its
    980 Hz line as "980 ± 4.9e+02", as if it might lie anywhere from 490 to 1470 Hz)."""
    if whole_periods:
        return f"{peak_Hz:.6g}"
    if not (resolution_Hz > 0 and math.isfinite(resolution_Hz)):
        return f"{peak_Hz:.4g} ± {resolution_Hz:.2g}"
    decimals = max(0, 1 - math.floor(math.log10(float(f"{resolution_Hz:.2g}"))))
    return f"{peak_Hz:.{decimals}f} ± {resolution_Hz:.2g}"


def spectrum_section(r: Report) -> Section:
    rows = []
    for s in r.stages:
        sp = s.spectrum
        peak = "–" if sp.peak_frequency_Hz is None else peak_text(sp.peak_frequency_Hz, sp.resolution_Hz,
                                                                    sp.whole_periods)
        rows.append((str(s.stage), peak, "–" if sp.peak_frequency_Hz is None else figure(sp.peak_amplitude_N, 3),
                     g(sp.mesh_frequency_Hz, 4), sp.matches))
    notes = []
    if r.stages:
        sp = r.stages[0].spectrum
        how = ("less its mean, whole periods (every line on a bin, a harmonic of the period, no window function: the "
               "frequencies and amplitudes exact)"
               if sp.whole_periods else "detrended, with a Hann window")
        notes.append(f"FFT of F_t over {sp.window_s[0]:.4g}–{sp.window_s[1]:.4g} s, {how}: "
                     f"resolution 1/T = {sp.resolution_Hz:.3g} Hz, Nyquist {sp.nyquist_Hz:.4g} Hz")
    nat = r.natural_frequencies_Hz
    notes.append("linearised natural frequencies [Hz]: " + (", ".join(f"{f:.4g}" for f in nat) if nat else "none given"))
    return Section("Dominant frequency of each mesh force", ("stage", "peak [Hz]", "amplitude [N]",
                                                             "mesh frequency [Hz]", "nearest line"),
                   tuple(rows), "lrrrl", tuple(notes))


def mesh_orders_section(r: Report) -> Section:
    rows = []
    errors = {e.stage: e.spectrum_N for st in r.simulation.stages if (e := st.error_estimate) is not None}
    below = False
    quiet, aliased = [], []
    for s in r.stages:
        err = errors.get(s.stage)
        if not s.spectrum.mesh_orders:  # nothing fluctuates, or too few samples (JSON: mesh_orders []): a row says so
            quiet.append((str(s.stage), s.spectrum.matches))
            rows.append((str(s.stage), "–", "–", "–", "–"))
        for o in s.spectrum.mesh_orders:
            if o.tangential_N is None:  # at or above the samples' Nyquist frequency: an alias, not an amplitude
                aliased.append(f"{s.stage} ({o.order}x)")
                rows.append((str(s.stage), f"{o.order}x", g(o.frequency_Hz, 5), "> Nyquist", "> Nyquist"))
                continue
            if err is not None and o.tangential_N < err:  # not resolved: only its bound is a number
                below = True
                dte = f"< {bound_text(err * o.dte_um / o.tangential_N, 2)}" if o.tangential_N > 0 and o.dte_um is not None \
                    else "–"
                rows.append((str(s.stage), f"{o.order}x", g(o.frequency_Hz, 5), f"< {bound_text(err, 2)}", dte))
                continue
            rows.append((str(s.stage), f"{o.order}x", g(o.frequency_Hz, 5), g(o.tangential_N, 4), g(o.dte_um, 4)))
    periodic = bool(r.stages) and r.stages[0].spectrum.whole_periods
    how = ("the window holds whole periods of the repeating response: the discrete Fourier coefficient, exact for "
           "each order" if periodic else "Hann-weighted projection of the detrended window (not whole periods)")
    notes = [f"amplitude of h x the mesh frequency in F_t and in the dynamic transmission error; {how}"]
    if aliased:
        notes.append(f"stage {', '.join(aliased)}: '> Nyquist', the order lies at or above the Nyquist frequency of the "
                     "output samples (less one resolution bin), where they alias it: no amplitude; raise "
                     "simulation.steps to see it")
    for why in dict.fromkeys(w for _, w in quiet):
        stages = ", ".join(k for k, w in quiet if w == why)
        reason = ("no fluctuation of F_t in the steady window (nothing excites the mesh)" if why == "no fluctuation"
                  else why)
        notes.append(f"stage {stages}: '–', {reason}, so no mesh-order amplitude")
    if below:
        notes.append("'< e': the computed amplitude is below e, the run's estimated error of its F_t spectrum (the "
                     "check pass's largest amplitude difference): not resolved, the amplitude is below about 2e")
    return Section("Mesh-order amplitudes", ("stage", "order", "frequency [Hz]", "F_t amplitude [N]",
                                             "DTE amplitude [µm]"), tuple(rows), "lrrrr", tuple(notes))


def error_cell(run: AccuracyRun, quantity: str, ref: ReferenceRun) -> str:
    """A rung's error of one quantity, or ``< u`` with u the reference's resolution of that quantity."""
    e = run.error(quantity)
    if e is None:
        return "–"
    if run.below_reference_resolution.get(quantity):
        return f"< {bound_text(ref.resolution(quantity), 2, 'e')}"
    return f"{e:.2e}"


def wall_text(wall_s: float) -> str:
    """A wall time in ms resolution, and two significant digits below 10 ms: a compiled rung of a few hundred
    evaluations takes ~0.3 ms, which "0.000" showed as no time at all."""
    return f"{wall_s:.3f}" if wall_s >= 0.01 or wall_s == 0 else f"{wall_s:.2g}"


def accuracy_section(study: AccuracyStudy) -> Section:
    ref, rec = study.reference, study.recommended
    rows: list[tuple[str, ...]] = []
    for run in study.runs:
        marks = " ".join(m for m, on in (("★", run is rec), ("file", run.file_settings)) if on)
        method = run.method if run.method == run.method_used else f"{run.method} ({run.method_used})"
        method += " [compiled]" if run.engine == "compiled" else ""
        if run.failure:
            rows.append((method, f"{run.rtol:.0e}", "–", "–", "–", "–", "–", run.failure[:60] + (" " + marks if marks else "")))
            continue
        cells = [error_cell(run, q, ref) for q in ("speed", "mean_force", "peak_force")]
        rows.append((method, f"{run.rtol:.0e}", wall_text(run.wall_s), str(run.nfev), *cells,
                     ("yes" if run.meets_accuracy else "no") + (f"  {marks}" if marks else "")))
    return Section(f"Numerical accuracy: work against precision (target {study.requested_accuracy:g})",
                   ("method", "rtol", "wall [s]", "nfev", "error ω_out", "error mean F_t", "error peak F_t",
                    "meets"), tuple(rows), "lrrrrrrl", tuple(accuracy_notes(study)))


def accuracy_notes(study: AccuracyStudy) -> list[str]:
    ref, rec, fr = study.reference, study.recommended, study.file_run
    notes = [
        f"reference: {ref.method} at rtol {ref.rtol:g} ({ref.wall_s:.2f} s, nfev {ref.nfev}); checked against "
        f"{ref.check_method} at rtol {ref.check_rtol:g} ({ref.check_wall_s:.2f} s): uncertainty {ref.uncertainty:.1e} "
        f"(largest relative difference; ω_out {ref.resolution('speed'):.1e}, mean F_t "
        f"{ref.resolution('mean_force'):.1e}, peak F_t {ref.resolution('peak_force'):.1e}); '< u' = below the "
        "reference's resolution of that quantity, u",
        "★ cheapest meeting the target: " + (f"{rec.method} at rtol {rec.rtol:g} ({wall_text(rec.wall_s)} s, nfev {rec.nfev})"
                                             if rec else "none"),
    ]
    if fr is not None:
        notes.append(f"the file's settings ({fr.method}, rtol {fr.rtol:g}) "
                     + ("meet" if study.file_settings_meet_accuracy else "do NOT meet")
                     + f" the target {study.requested_accuracy:g} in the three quantities compared (ω_out, mean and "
                     "peak F_t); the window's min, max and std have their own estimate, the run's "
                     "statistics_unresolved and statistics_undersampled warnings")
    notes.append("error peak F_t: the solver's, every run on the same output samples; the peaks the samples miss "
                 "between them are the sampling error of section \"Dynamic factor and run-up peak\"")
    return notes + list(study.notes)


def solver_lines(r: Report) -> list[str]:
    sv, sim = r.simulation.solver, r.simulation
    return [
        f"solver {sv.method} ({sv.choice_reason}), rtol {sv.rtol:g}: {sv.steps} steps, nfev {sv.nfev}, "
        f"njev {sv.njev}, wall {sv.wall_s:.3g} s" + (f" (the result's {sv.runs} runs: nfev {sv.total_nfev}, wall "
                                                     f"{sv.total_wall_s:.3g} s)" if sv.runs > 1 else ""),
        f"energy balance residual {sv.energy_residual:.2e} (input work − load work − damping loss − ΔKE − ΔPE, "
        "relative to the largest energy)",
        f"dynamic ratio {sim.ratio:.6g}, output {_output_speed(sim)}",
    ]


def _output_speed(sim) -> str:
    """The window-mean output speed in the design file's speed unit, as `simulate`'s footer (°/s files: also rpm;
    rad/s files: also rpm)."""
    return of_result(sim).speed_text(sim.output_speed_deg_s)


def rating_section(r: Report) -> Section | None:
    """ISO K_v beside the simulated K_v (``Report.rating``), one row per rated stage."""
    rows = tuple((str(c.stage), f"{c.K_v_iso:.4g} ({c.K_v_iso_source})", g(c.K_v_simulated, 4),
                  g(c.min_S_H_iso, 3), g(c.min_S_F_iso, 3), g(c.min_S_H_simulated, 3), g(c.min_S_F_simulated, 3))
                 for c in r.rating)
    if not rows:
        return None
    # the design's K_v is ISO 6336-1's under ISO 6336; a plug-in standard's (docs/plugins.md) is its own
    # lazy: start-up time, the rating's modules load only for a rated report
    from gearcli.design.iso6336 import ISO6336

    title = next(st.rating.standard for st in r.design.stages if st.rating is not None)
    iso = title == ISO6336.title
    return Section("Dynamic factor: " + ("ISO 6336-1" if iso else shorten(title, 80)) + " against the simulation",
                   ("stage", "K_v ISO" if iso else "K_v design", "K_v simulated", "min S_H", "min S_F", "min S_H sim.", "min S_F sim."),
                   rows, "lrrrrrr",
                   ("K_v simulated = max(1, steady-window max |F_t| / static F_t); the safeties at it are rated "
                    'with [rating] dynamic_factor = "simulated"',))


def _driver(s):
    """The driving member of a stage in the housing's frame: a parallel stage's pinion, a planetary's input member
    (sun, carrier or ring; not the sun–planet pair's pinion, whose speed is relative to the carrier)."""
    return s.pinion if s.planetary is None else getattr(s.planetary, s.planetary.input)


def design_section(r: Report) -> Section:
    """The geometry and loads of each stage: what the engineer checks first."""
    u = of_result(r.simulation)
    speeds, torques = u.table_speeds(), u.table_torques()
    st = r.design.stages
    # a planetary stage's pinion is its sun in the carrier's frame (a relative speed, one planet's share of the
    # torque): its column shows the stage's input member in the housing's frame, as design's member table does
    driver = "pinion" if all(s.planetary is None for s in st) else "pinion (planetary: input member)"
    rows = [
        ("teeth z1 / z2", *(f"{s.pinion.teeth} / {s.gear.teeth}" for s in st)),
        ("ratio", *(g(s.ratio, 5) for s in st)),
        ("normal module m_n [mm]", *(g(s.normal_module_mm) for s in st)),
        ("helix angle β [°]", *(g(s.helix_angle_deg) for s in st)),
        ("centre distance a [mm]", *(g(s.center_distance_mm, 6) for s in st)),
        ("face width b [mm]", *(g(s.face_width_mm) for s in st)),
        ("contact ratios ε_α / ε_β", *(f"{s.contact_ratio_transverse:.3f} / {s.overlap_ratio:.3f}" for s in st)),
        # the file's units, and as every table (docs/output.md, "Units") rpm beside °/s or rad/s, N·m beside N·mm
        *((f"{driver} speed [{unit}]", *(g(f(_driver(s).speed_deg_s), 6) for s in st)) for unit, f in speeds),
        *((f"{driver} torque [{unit}]", *(g(f(_driver(s).torque_Nmm), 6) for s in st)) for unit, f in torques),
        ("mesh frequency [Hz]", *(g(s.mesh_frequency_Hz) for s in st)),
        ("static F_t [N]", *(g(s.static_force_N.tangential) for s in st)),
        ("mesh stiffness c_γα [N/(mm·µm)]", *(g(s.iso6336_mesh_stiffness_N_mm_um, 4) for s in st)),
    ]
    d = r.design
    def each(value: float, units) -> str:  # "8700 °/s = 1450 rpm"
        return " = ".join(f"{g(f(value), 6)} {unit}" for unit, f in units)

    notes = (f"total ratio {d.total_ratio:.6g}; input {each(d.input_speed_deg_s, speeds)}, "
             f"output {each(d.output_speed_deg_s, speeds)}; input torque {each(d.input_torque_Nmm, torques)}, "
             f"input power {d.input_power_kW:.5g} kW",)
    return Section("Design", ("quantity", *(f"stage {s.index}" for s in st)), tuple(rows),
                   "l" + "r" * len(st), notes)


def modes_section(r: Report) -> Section | None:
    """Natural frequencies, modal damping, dominant element and the orders near the nominal speed."""
    ana = r.modes
    if ana is None:
        return None
    rows = []
    for m in ana.modes:
        if m.rigid:
            rows.append((str(m.number), "0", "–", "–", "rigid-body rotation", "–"))
            continue
        near = [c for c in m.crossings if c.input_speed_rpm is None  # a fixed frequency near the mode: at any speed
                or near_nominal(c.input_speed_rpm, ana.nominal_input_rpm)]
        u = of_result(r.simulation)
        cross = ", ".join(f"{c.excitation} at " + ("any speed" if c.input_speed_rpm is None else
                                                   f"{u.speed_from_deg_s(6.0 * c.input_speed_rpm):.4g} "
                                                   f"{u.speed_label}") + f" ({c.strength})"
                          for c in near) or "none"
        rings = "–" if m.damped_frequency_Hz is None else g(m.damped_frequency_Hz, 5)  # where zeta's eigenvalue rings
        rows.append((str(m.number), g(m.frequency_Hz, 5), figure(100 * m.damping_ratio, 2), rings,
                     f"{m.dominant} ({100 * max(m.energy_share):.0f} %)", cross))
    return Section("Modes and resonances", ("mode", "f [Hz]", "ζ [%]", "rings at [Hz]", "dominant element (strain energy)",
                                            f"orders within ±{100 * RESONANCE_BAND:.0f} % of the mode at the nominal speed"),
                   tuple(rows), "lrrrll",
                   (f"linearised at full load, {ana.boundary.replace('_', ' ')}; "
                    "the Campbell diagram (all orders 0 … 1.2 × nominal) is campbell.png with --plots",))


def sections(r: Report) -> list[Section]:
    """Engineering first (design, modes, theory against simulation), the numerical study after it."""
    out = [design_section(r)]
    rating = rating_section(r)  # ISO K_v against the simulated one, after the design
    if rating is not None:
        out.append(rating)
    modes = modes_section(r)
    if modes is not None:
        out.append(modes)
    out += [comparison_section(r), peaks_section(r), fluctuation_section(r), spectrum_section(r),
            mesh_orders_section(r)]
    if r.accuracy is not None:
        out.append(accuracy_section(r.accuracy))
    return out


def method_paragraph(study: AccuracyStudy, report_window_s: tuple[float, float] | None = None) -> str:
    """How the numbers of the accuracy study were obtained, for a reader of the markdown report. ``report_window_s``:
    the window of the report's own run, which the settle test may have moved past the study's (the file's)."""
    ref = study.reference
    window = "the steady window"
    if ref.window_s is not None:
        w0, w1 = ref.window_s
        window = f"the window {w0:.4g}–{w1:.4g} s"
        if report_window_s is not None and not all(
                abs(a - b) <= 1e-9 * max(1.0, abs(b)) for a, b in zip(ref.window_s, report_window_s, strict=True)):
            window += (f" (the file's, as every run of the study takes it; the sections above use the window "
                       f"{report_window_s[0]:.4g}–{report_window_s[1]:.4g} s, where the run is settled)")
    # the ladder's grid: every method at every rtol; the file's own setting, where it is no rung, is named apart
    rungs = [r for r in study.runs if not (study.file_run_extra and r.file_settings)]
    rtols = sorted({r.rtol for r in rungs}, reverse=True)
    methods = list(dict.fromkeys(r.method for r in rungs))
    file = study.file_run
    besides = (f", and the file's own setting, {file.method} at rtol {file.rtol:g}" if study.file_run_extra
               and file is not None else "")
    return (
        f"The scene was run with {', '.join(methods)} at rtol {', '.join(f'{x:g}' for x in rtols)}{besides}. "
        f"Each run's error is relative to a reference run ({ref.method} at rtol {ref.rtol:g}). The reference was "
        f"checked by an independent run with a different method ({ref.check_method} at rtol {ref.check_rtol:g}); "
        f"the largest relative difference between the two over the compared quantities, {ref.uncertainty:.1e}, "
        f"is the reference's own uncertainty; each quantity's own difference is the reference's resolution of it, "
        f"and an error below its quantity's resolution is reported as below the reference resolution "
        f"(\"< u\": ω_out {ref.resolution('speed'):.1e}, mean F_t {ref.resolution('mean_force'):.1e}, peak F_t "
        f"{ref.resolution('peak_force'):.1e}). Compared quantities: the mean output speed over {window}, the mean "
        f"F_t (largest relative error over the stages) and the run-up peak |F_t| (largest over the stages). A "
        f"setting meets the target {study.requested_accuracy:g} when max(error, uncertainty) is within it for all "
        f"three; ★ marks the cheapest such setting, priced as its evaluations times its method's median "
        f"integration time per evaluation over the ladder (one run's wall time is too noisy to rank neighbouring "
        f"rungs). Wall times are single measurements on this machine and move with its load (a rung of a few "
        f"milliseconds by up to several-fold from one report to the next); the evaluations (nfev) are the repeatable "
        f"measure of work."
    )
