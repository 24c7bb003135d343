"""The compiled integration engine: the whole integration loop as machine code (the ``fast`` extra, numba).

``[simulation] engine``: ``python`` is scipy's integrators around the generated right-hand side
(:mod:`gearcli.simulate.solver`); ``compiled`` runs :mod:`gearcli.engine.kernel`, which reads the model as
arrays (:class:`gearcli.model.ModelArrays`): DOP853 and RK45 take exactly scipy's steps, Radau scipy's
algorithm (its results agree with scipy's to the tolerance); ``auto`` picks per run (:func:`gearcli.engine.choose`).

What the kernel supports is listed in :data:`SUPPORTED`; :func:`unsupported` names every feature of a scene
outside it, and such a scene runs on the Python engine with that reason in ``solver.engine_reason``
(never silently wrong).

Compilation: once per installation (and after an upgrade of gearcli or numba; ``gearcli engine build`` does it
ahead), cached on disk under the user's cache directory (``$XDG_CACHE_HOME/gearcli/numba``, else
``~/.cache/gearcli/numba``), in a subdirectory named by a hash of the kernel's and the element laws' sources and
numba's version, so a changed element law never runs stale machine code; the cache's safety, its repair and the
first build's progress: :mod:`gearcli.engine.loader`.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Iterator
from contextlib import contextmanager

import numpy as np

from gearcli.core.cost import COMPILE_S, MIN_LOAD_S, REFERENCE_KEEP_S, predicted_wall_s
from gearcli.core.methods import METHODS
from gearcli.core.records import record
from gearcli.engine.loader import (  # noqa: F401 - the package's interface
    Built,
    LineReporter,
    Loaded,
    _state,
    available,
    build,
    cache_choice,
    cache_dir,
    cache_problem,
    cache_root,
    cached_or_loaded,
    compilation_pending,
    entry,
    expected_load_s,
    import_kernel,
    import_problem,
    load,
    loaded_kernel,
    mark_ready,
    point_functions,
    quiet_compilation,
    ready,
    warm_up,
)
from gearcli.engine.packing import _acting_on, pack  # noqa: F401 - the package's interface
from gearcli.errors import ConfigError
from gearcli.model import elements

ENGINES = ("auto", "python", "compiled")
COMPILED_METHODS = tuple(n for n, m in METHODS.items() if "compiled" in m.engines)  # the registry's word
# take scipy's steps bit for bit (RK45's samples agree to the last bits: its interpolant is summed in a loop);
# Radau's LU differs from LAPACK's in the last bit, and its steps part after a while (tests of the port; what a
# user is promised is agreement to the tolerance)
BIT_IDENTICAL = ("DOP853", "RK45")
INSTALL_HINT = "pip install 'gearcli[fast]'"
SUPPORTED = (
    "connectors: torsional springs (couplings, flexible shafts) and gear meshes (Adams IMPACT law: Hertz or "
    "linear stiffness, backlash on both flanks, STEP damping ramp, no tension)",
    "time-varying mesh stiffness from the contact-line length",
    "mesh excitation: transmission error (the law on q = delta - e), stiffness harmonics, viscous damping ratio",
    "speed drive (exact STEP speed profile, start angle) or torque drive with torque ripple, STEP-ramped; "
    "STEP-ramped load torque with load fluctuation (clock offset)",
    "induction-motor drive (extended Kloss or table curve; direct, star-delta, soft start, VFD); speed-dependent "
    "load (power law or table); losses of any compiled element with the loss hook (a mesh's stage efficiency in the "
    "power-flow direction)",
    "a run that starts at t0 > 0 (the periodic steady state's period-by-period runs, sweep continuation)",
    "energy quadratures (input work with the transmission error's work, load work, damping loss, work on "
    "time-varying springs)",
    "method DOP853 (scipy's steps, error norm, step control and dense output, bit for bit)",
    "method RK45 (scipy's steps bit for bit; samples to the last bits)",
    "method Radau (scipy's Radau IIA: Newton iteration, LU reuse, error estimate, step control, dense output; "
    "analytic Jacobian from the elements' partials)",
)
# ModelArrays fields the kernel reads; any other field with content is a feature it does not know
_KNOWN_FIELDS = {"body_inertia", "conn_kind", "conn_bodies", "conn_levers", "conn_param", "body_tree",
                 "drive_kind", "drive_value", "drive_ramp_s", "drive_ripple", "drive_angle_rad", "load_value_Nm",
                 "load_ramp_s", "load_fluct", "load_clock_s", "n_states", "i_delta0", "i_omega0", "i_theta", "i_quad", "atol",
                 "motor_row", "load_law", "body_angle_row", "i_quadratures", "conn_loss_bodies", "conn_loss_speeds",
                 "conn_loss_shares"}


def _known_params() -> dict[int, int]:
    """Entries of each compiled kind's parameter row its law reads (``ROW_WIDTH``, else its ``PARAMS``; a
    mesh's: all, harmonics included)."""
    return {et.kind: getattr(et.law, "ROW_WIDTH", len(et.law.PARAMS)) for et in elements.compiled_types()}


def unsupported(arrays, method: str) -> list[str]:
    """The features of a scene (its model arrays and integration method) the kernel does not support;
    empty when the compiled engine can run it."""
    out = []
    if method not in COMPILED_METHODS:
        out.append(f"method {method} (the compiled engine integrates {', '.join(COMPILED_METHODS)} only)")
    kept = getattr(arrays, "__dict__", {}).get("_unsupported")  # the scene's own part: once per model's arrays
    if kept is None:
        kept = _scene_unsupported(arrays)
        if hasattr(arrays, "__dict__"):
            arrays.__dict__["_unsupported"] = kept
    return out + list(kept)


def _scene_unsupported(arrays) -> tuple[str, ...]:
    """:func:`unsupported`'s features of the scene itself (its arrays, whatever the method)."""
    out = []
    known = _known_params()
    kinds = {int(k) for k in np.asarray(arrays.conn_kind)}
    if kinds - set(known):
        out.append(f"connector kinds {sorted(kinds - set(known))}")
    param = np.asarray(arrays.conn_param)
    for c, k in enumerate(np.asarray(arrays.conn_kind).tolist()):
        if k in known and param[c, known[k]:].any():  # (an entry that is not 0.0: NaN too, as != 0.0)
            out.append(f"element parameters beyond the known ones on connector {c}")
            break
    for f in dataclasses.fields(arrays):
        if f.name not in _KNOWN_FIELDS and _has_content(getattr(arrays, f.name)):
            out.append(f"model feature {f.name!r}")
    return tuple(out)


def _has_content(v) -> bool:
    if v is None or v is False:
        return False
    a = np.asarray(v)
    if a.dtype == object:
        return True
    return bool(a.size) and bool(np.any(a != 0))


# ------------------------------------------------------------------------------------------- auto
# What a run costs on either engine: gearcli.core.cost (one price per evaluation and engine, measured).
_runs = {"expected": 1, "active": 0}
_fixed_share: list[float] = []  # a reproducible batch's price per run of loading the kernel (innermost last)


def expect_runs(n: int) -> None:
    """Tell ``auto`` that this process will integrate about ``n`` more runs (a report's ladder, a sweep's
    task): the one-time cost of loading the kernel is shared by all the runs announced in the process (a
    sweep worker that gets one point per task switches once its points have added up)."""
    _runs["expected"] += max(0, int(n))


@contextmanager
def batch(n: int, load_share_s: float | None = None) -> Iterator[None]:
    """A batch of about ``n`` runs (a report's ladder, a sweep task), announced to ``auto`` (:func:`expect_runs`).
    ``load_share_s`` (a sweep's: :func:`sweep_load_share_s`): each run of the batch prices loading the kernel at
    that, whether this process has loaded it yet or not, so that the engine a run takes, and so its numbers,
    depend on neither which process ran it, nor what it ran before, nor the machine's load."""
    expect_runs(n)
    _runs["active"] += 1
    if load_share_s is not None:
        _fixed_share.append(load_share_s)
    try:
        yield
    finally:
        _runs["active"] -= 1
        if load_share_s is not None:
            _fixed_share.pop()


def reproducible() -> bool:
    """Whether a reproducible batch (a sweep's task: :func:`batch` with a load share) is running."""
    return bool(_fixed_share)


def sweep_load_share_s(points: int) -> float:
    """A sweep's price per point of loading the kernel, the same for every point whatever the sweep's split into
    tasks and workers, a resume, or what a worker has loaded (:mod:`gearcli.sweep.execute` computes it once, in
    the parent): nothing where the kernel is cached (each worker loads it once, ~0.1-0.6 s, ``DEFAULT_LOAD_S``,
    against a sweep's many runs), a compilation's ``COMPILE_S`` over all the sweep's points where it is not."""
    if not available():
        return 0.0  # without numba: no engine to price
    return 0.0 if cached_or_loaded() else COMPILE_S / max(1, points)


def load_share_s() -> float:
    """What loading the compiled engine still costs each announced run of this process (0 once loaded; a
    reproducible batch's fixed share, :func:`batch`)."""
    if _fixed_share:
        return _fixed_share[-1]
    return expected_load_s() / _runs["expected"]


def options(requested: str, arrays, methods: tuple[str, ...], also: tuple[str, ...] = ()) -> dict[str, dict[str, float]]:
    """Per method, the engines that may run it under ``requested`` and what loading each still costs this
    process: what ``auto``'s method choice prices (:func:`gearcli.simulate.choice.predicted_costs`). The method is
    chosen at the compiled engine's prices wherever it may run; :func:`choose` may still keep a short one-shot
    Radau run on scipy (``REFERENCE_KEEP_S``), so that the choice of the method does not depend on whether this
    process happens to have loaded the kernel."""
    out: dict[str, dict[str, float]] = {}
    compiled_ok = requested != "python" and available()
    share: list[float] = []  # what loading costs is one number for every method (its cache is read once)
    for m in methods:
        opts = {"python": 0.0} if requested != "compiled" else {}
        if compiled_ok and not unsupported(arrays, m) and not also:
            share = share or [load_share_s()]
            opts["compiled"] = share[0]
        out[m] = opts or {"python": 0.0}
    return out


@record
class EngineChoice:
    """The engine a run takes (python or compiled) and why."""

    engine: str  # "python" or "compiled"
    requested: str
    reason: str
    unsupported: tuple[str, ...] = ()


def compiled_problem() -> str | None:
    """Why ``engine = "compiled"`` cannot run in this process, in the words of its usage error (numba, the ``fast``
    extra, not installed, or installed but not importable: the extra named), or None when it can (imports numba,
    as a compiled run does anyway)."""
    if not available():
        return f'engine = "compiled" needs numba, the fast extra: {INSTALL_HINT}'
    why = None if "loaded" in _state else import_problem()
    if why is not None:
        return (f'engine = "compiled" needs numba, the fast extra, and numba is installed but cannot be imported '
                f"({why}): pip install --force-reinstall 'gearcli[fast]'")
    return None


def choose(requested: str, arrays, method: str, nfev_estimate: float, also: tuple[str, ...] = (),
           size=None) -> EngineChoice:
    """The engine of one run. ``compiled`` without numba raises :class:`~gearcli.errors.ConfigError`
    (a usage error naming the extra); a scene the kernel does not support (or with the caller's reasons
    ``also``) runs on Python with the reason.

    ``auto`` takes the compiled engine for every method it has (Radau included, one-shot runs too: its results
    agree with scipy's to the tolerance; a one-shot run of such a method only when it saves at least
    ``REFERENCE_KEEP_S``, else scipy's reference numbers) when it is installed, supports the scene, and is predicted faster
    including what loading it still costs this process (numba import and cache load, measured on the last
    load; nothing once loaded; a full compilation when nothing is cached, so that a one-shot run never waits
    for the compiler), that load shared by the runs announced with :func:`expect_runs`. The prices:
    :mod:`gearcli.core.cost` (``size``: the model's :class:`~gearcli.core.cost.ModelSize`, for its price per
    evaluation on each engine).
    """
    if requested == "python":
        return EngineChoice("python", requested, "as requested")
    have = available()
    if requested == "compiled" and not have:
        raise ConfigError(str(compiled_problem()), key="simulation.engine")
    missing = tuple(unsupported(arrays, method)) + tuple(also)
    if missing:
        return EngineChoice("python", requested, "the compiled engine does not support " + "; ".join(missing),
                            missing)
    if requested == "compiled" and (problem := compiled_problem()) is not None:
        raise ConfigError(problem, key="simulation.engine")
    if requested == "compiled":
        return EngineChoice("compiled", requested, "as requested")
    if not have:
        return EngineChoice("python", requested, f"numba is not installed ({INSTALL_HINT} for the compiled engine)")
    python_s = predicted_wall_s("python", method, nfev_estimate, size=size)
    if not _fixed_share and "loaded" not in _state and python_s < MIN_LOAD_S / _runs["expected"]:  # not worth even a look at the cache
        return EngineChoice("python", requested, f"~{nfev_estimate:.2g} evaluations take ~{python_s:.2g} s in Python, "
                            f"less than importing numba alone (~{MIN_LOAD_S:g} s)")
    load_s = load_share_s()
    compiled_s = predicted_wall_s("compiled", method, nfev_estimate, load_s, size)
    if method not in BIT_IDENTICAL and _runs["active"] == 0 and python_s - compiled_s < REFERENCE_KEEP_S:
        return EngineChoice("python", requested, f"~{nfev_estimate:.2g} evaluations: the compiled {method} (which "
                            f"agrees with scipy to the tolerance, not step for step) would save less than "
                            f"{REFERENCE_KEEP_S:g} s of ~{python_s:.2g} s: scipy's, the reference")
    if compiled_s < python_s and "loaded" not in _state and (why := import_problem()) is not None:
        return EngineChoice("python", requested, f"numba is installed but cannot be imported ({why})")
    if compiled_s < python_s:
        return EngineChoice("compiled", requested, f"~{nfev_estimate:.2g} evaluations: ~{compiled_s:.2g} s compiled "
                            f"(load included) against ~{python_s:.2g} s in Python")
    return EngineChoice("python", requested, f"~{nfev_estimate:.2g} evaluations take ~{python_s:.2g} s in Python, less "
                        f"than loading the compiled engine (~{load_s:.2g} s)")
