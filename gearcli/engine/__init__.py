"""The compiled integration engine: the whole integration loop as machine code (the ``fast`` extra, numba).

``[simulation] engine``: ``python`` is scipy's integrators around the generated right-hand side
(:mod:`gearcli.simulate.solver`); ``compiled`` runs :mod:`gearcli.engine.kernel`, which reads the model as
arrays (:class:`gearcli.model.ModelArrays`): DOP853 and RK45 take exactly scipy's steps, Radau scipy's
algorithm (its results agree with scipy's to the tolerance); ``auto`` picks per run (:func:`gearcli.engine.choose`).

What the kernel supports is listed in :data:`SUPPORTED`; :func:`unsupported` names every feature of a scene
outside it, and such a scene runs on the Python engine with that reason in ``solver.engine_reason``
(never silently wrong).

Compilation: once per installation (and after an upgrade of gearcli or numba), cached on disk under the
user's cache directory (``$XDG_CACHE_HOME/gearcli/numba``, else ``~/.cache/gearcli/numba``), in a
subdirectory named by a hash of the kernel's and the element laws' sources and numba's version, so a changed
element law never runs stale machine code. The first compilation says so on stderr.
"""

from __future__ import annotations

import dataclasses
import hashlib
import importlib.util
import json
import os
import sys
import tempfile
import time
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from gearcli.core.cost import COMPILE_S, DEFAULT_LOAD_S, MIN_LOAD_S, REFERENCE_KEEP_S, predicted_wall_s
from gearcli.core.methods import METHODS
from gearcli.engine import blas
from gearcli.errors import ConfigError
from gearcli.model import elements, outputs
from gearcli.model.elements import machine

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
    "load (power law or table); mesh losses (stage efficiency in the power-flow direction)",
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
                 "motor_row", "load_law", "body_angle_row"}
_SOURCES = ("engine/kernel.py", "engine/dispatch.py", "engine/tableau.py", "engine/blas.py", "engine/status.py", "model/elements/__init__.py",
            "model/elements/torque.py", "model/elements/machine.py", "model/contact_lines.py")  # + every compiled element's module (_source_key)

_state: dict = {}


def available() -> bool:
    """Whether numba (the ``fast`` extra) is installed."""
    if "numba" in sys.modules:
        return sys.modules["numba"] is not None
    return importlib.util.find_spec("numba") is not None


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
    known = _known_params()
    kinds = {int(k) for k in np.asarray(arrays.conn_kind)}
    if kinds - set(known):
        out.append(f"connector kinds {sorted(kinds - set(known))}")
    param = np.asarray(arrays.conn_param)
    for c, k in enumerate(np.asarray(arrays.conn_kind)):
        if int(k) in known and np.any(param[c, known[int(k)]:] != 0.0):
            out.append(f"element parameters beyond the known ones on connector {c}")
            break
    for f in dataclasses.fields(arrays):
        if f.name not in _KNOWN_FIELDS and _has_content(getattr(arrays, f.name)):
            out.append(f"model feature {f.name!r}")
    return out


def _has_content(v) -> bool:
    if v is None or v is False:
        return False
    a = np.asarray(v)
    if a.dtype == object:
        return True
    return bool(a.size) and bool(np.any(a != 0))


def _usable_dir(path: Path) -> str | None:
    """Why ``path`` cannot hold the cache (None: it can): it must be absolute and be, or become, a writable
    directory."""
    if not path.is_absolute():
        return "not an absolute path"
    probe = path
    while not probe.exists() and probe != probe.parent:
        probe = probe.parent
    if not probe.is_dir():
        return f"{probe} is not a directory"
    if not os.access(probe, os.W_OK | os.X_OK):
        return f"{probe} is not writable"
    return None


def cache_choice() -> tuple[Path, str]:
    """The cache root and, when ``$XDG_CACHE_HOME`` (or the home directory) cannot hold it, why another one is
    used ('' when the first choice is used): $XDG_CACHE_HOME, else ~/.cache, else the temporary directory."""
    why = ""
    xdg = os.environ.get("XDG_CACHE_HOME")
    candidates = [("XDG_CACHE_HOME", Path(xdg))] if xdg else []
    candidates += [("~/.cache", Path(os.path.expanduser("~")) / ".cache"),
                   ("the temporary directory", Path(tempfile.gettempdir()) / f"gearcli-{os.getuid()}"
                    if hasattr(os, "getuid") else Path(tempfile.gettempdir()) / "gearcli")]
    for name, base in candidates:
        root = base / "gearcli" / "numba" if name != "the temporary directory" else base / "numba"
        problem = _usable_dir(root)
        if problem is None:
            return root, why
        why = why or f"{name} cannot hold the cache ({problem})"
    return candidates[-1][1] / "numba", why


def cache_root() -> Path:
    return cache_choice()[0]


def _source_key() -> str:
    h = hashlib.sha1()
    pkg = Path(__file__).resolve().parent.parent
    for rel in _SOURCES:
        h.update((pkg / rel).read_bytes())
    for et in elements.compiled_types():  # the registry: what the generated dispatch calls, and the laws' code
        h.update(f"{et.kind}:{et.name}:{et.law.__name__}".encode())
        h.update(Path(et.law.__file__ or "").read_bytes())
    h.update(blas.KEY.encode())
    spec = importlib.util.find_spec("numba")  # the installed numba (its path and version stamp), without importing it
    if spec is not None and spec.origin:
        h.update(f"{spec.origin}:{os.stat(spec.origin).st_mtime_ns}".encode())
    return h.hexdigest()[:16]


def cache_dir() -> Path:
    """Where the compiled kernel is cached (one subdirectory per kernel source and numba version)."""
    return cache_root() / _source_key()


@dataclass(frozen=True)
class Loaded:
    kernel: Any  # the gearcli.engine.kernel module
    load_s: float  # numba import + cache load (or compilation), this process
    compiled: bool  # compiled now (no cache)


def load(quiet: bool = False) -> Loaded:
    """Import numba and the kernel, compile it or load it from the cache; once per process. The first
    compilation prints one line on stderr."""
    if "loaded" in _state:
        return _state["loaded"]
    t0 = time.perf_counter()
    cdir = cache_dir()
    marker = cdir / "ready.json"
    fresh = not marker.exists()
    try:
        cdir.mkdir(parents=True, exist_ok=True)
    except OSError:
        pass
    import numba  # noqa: F401  # lazy: numba, the optional fast extra, start-up time
    import numba.core.config as ncfg  # lazy: numba, the optional fast extra, start-up time

    ncfg.CACHE_DIR = str(cdir)  # type: ignore[attr-defined]
    if fresh and not quiet and not _state.get("quiet"):
        print(f"gearcli: compiling the integration engine once (about a minute); {_cache_words(cdir)}", file=sys.stderr)
    from gearcli.engine import kernel  # lazy: numba, the kernel compiles or loads its cache on import

    _warm_up(kernel)
    load_s = time.perf_counter() - t0
    if fresh:
        try:
            marker.write_text(json.dumps({"compile_s": load_s}))
        except OSError:
            pass
    else:
        _remember_load_time(load_s)
    _state["loaded"] = Loaded(kernel, load_s, fresh)
    outputs.use_compiled(kernel)  # the model's sampled outputs run the compiled laws from now on
    return _state["loaded"]


def _cache_words(cdir: Path) -> str:
    """Where the kernel is cached, and why not where the user pointed when that was unusable."""
    why = cache_choice()[1]
    return f"cached in {cdir}" + (f" ({why}; using this one instead)" if why else "")


def quiet_compilation() -> None:
    """This process does not announce a compilation (a sweep's pool worker: its parent announced it once)."""
    _state["quiet"] = True


def compilation_pending() -> str | None:
    """The one-line notice for a parent whose workers may compile the kernel (numba installed, nothing cached);
    None when nothing will be compiled."""
    if importlib.util.find_spec("numba") is None or (cache_dir() / "ready.json").exists():
        return None
    return (f"the sweep's workers may compile the integration engine once (about a minute, when a point runs on "
            f"it); {_cache_words(cache_dir())}")


def loaded_kernel() -> Any:
    """The kernel module when this process has loaded it, else None (never loads it)."""
    loaded = _state.get("loaded")
    return loaded.kernel if loaded is not None else None


def _remember_load_time(load_s: float) -> None:
    """The last measured numba import + cache load time (what ``auto`` weighs a one-shot run against)."""
    try:
        (cache_root() / "load_time.json").write_text(json.dumps({"load_s": load_s}))
    except OSError:
        pass


def expected_load_s() -> float:
    """What loading the kernel will cost this process: 0 when loaded, the last measured load time when
    cached, a compilation's when not."""
    if "loaded" in _state:
        return 0.0

    if not (cache_dir() / "ready.json").exists():
        return COMPILE_S
    try:
        return float(json.loads((cache_root() / "load_time.json").read_text())["load_s"])
    except (OSError, ValueError, KeyError, TypeError):
        return DEFAULT_LOAD_S


def _tiny_model():
    """Two bodies, one mesh and one spring: a model of every argument type, to compile or load once."""
    mesh = elements.mesh
    param = np.zeros((2, elements.N_PARAM))
    param[0, :13] = (1.0, 1.0, 1e9, 1.5, 1e3, 1e4, 6e7, 0.0, 0.0, 1.5, 1.0, 20.0, 1e-4)
    param[0, mesh.I_NTE], param[0, mesh.I_TE] = 1.0, 1e-6
    param[1, :2] = (1e4, 1.0)
    bodies = np.full((2, elements.MAX_BODIES), -1, dtype=np.int64)
    bodies[:, :2] = ((0, 1), (1, 2))
    levers = np.zeros((2, elements.MAX_BODIES))
    levers[:, :2] = ((0.1, -0.2), (1.0, -1.0))
    return (np.array([elements.KIND_MESH, elements.KIND_SPRING], dtype=np.int64), bodies, levers, param,
            np.array([1.0, 2.0, 3.0]), np.array([0, 2, -1, 4, 0, 0], dtype=np.int64),
            np.array([10.0, 0.01, 5.0, 0.01, 0.0, 0.0]), np.array([0.01, 2.0]), np.array([0.01, 5.0]),
            np.array([-1, 0, 1], dtype=np.int64), *_acting_on(bodies, 3), np.zeros(machine.M_TAB),
            np.zeros(machine.L_TAB), np.zeros((0, 0)))


def _warm_up(kernel) -> None:
    model = _tiny_model()
    y0 = np.zeros(7)
    t_eval = np.array([0.0, 1e-3])
    tol = np.full(7, 1e-6)
    kernel.dop853(model, y0, t_eval, np.array([1e-3]), tol, tol, np.int64(100), np.int64(16),
                  np.array([0.0, 0.0, 1.0, 0.1, 0.0]), np.empty(0))
    kernel.rk45(model, y0, t_eval, np.array([1e-3]), tol, tol, np.int64(100), np.int64(16),
                np.array([0.0, 0.0, 1.0, 0.1, 0.0]), np.empty(0))
    kernel.radau(model, y0, t_eval, np.array([1e-3]), tol, tol, np.int64(100), np.int64(16),
                 np.array([0.0, 0.0, 1.0, 0.1, 0.0]), np.empty(0))
    kernel.evaluate(model, 0.0, y0)
    kernel.evaluate_many(model, 0.0, y0, np.int64(1))
    for c in range(2):
        kernel.connector_series(model[0][c], model[3][c], np.zeros(2), np.zeros(2), np.zeros(2), np.zeros(2))


def pack(arrays) -> tuple:
    """The kernel's model tuple from :class:`~gearcli.model.ModelArrays`."""
    kind = np.ascontiguousarray(arrays.conn_kind, dtype=np.int64)
    bodies = np.ascontiguousarray(arrays.conn_bodies, dtype=np.int64)
    param = np.ascontiguousarray(arrays.conn_param, dtype=np.float64)
    laws = [elements.law_of(k) for k in kind]
    tv = [c for c in range(kind.size) if laws[c].time_varying(param[c])]
    phased = [c for c in range(kind.size) if laws[c].phased(param[c])]
    last_angle = max((int(bodies[c, 0]) for c in phased), default=0)
    ipar = np.array([arrays.drive_kind, arrays.i_omega0, arrays.i_theta, arrays.i_quad, last_angle, len(tv)],
                    dtype=np.int64)
    fpar = np.array([arrays.drive_value, arrays.drive_ramp_s, arrays.load_value_Nm, arrays.load_ramp_s,
                     arrays.drive_angle_rad, arrays.load_clock_s], dtype=np.float64)
    ripple = np.ascontiguousarray(np.asarray(arrays.drive_ripple, dtype=np.float64).reshape(-1))
    fluct = np.ascontiguousarray(np.asarray(arrays.load_fluct, dtype=np.float64).reshape(-1))
    ptr, pairs = _acting_on(bodies, len(arrays.body_inertia))
    return (kind, bodies, np.ascontiguousarray(arrays.conn_levers, dtype=np.float64), param,
            np.ascontiguousarray(arrays.body_inertia, dtype=np.float64), ipar, fpar, ripple, fluct,
            np.ascontiguousarray(arrays.body_tree, dtype=np.int64), ptr, pairs,
            np.ascontiguousarray(np.asarray(arrays.motor_row, dtype=np.float64).reshape(-1)),
            np.ascontiguousarray(np.asarray(arrays.load_law, dtype=np.float64).reshape(-1)),
            np.ascontiguousarray(np.atleast_2d(np.asarray(arrays.body_angle_row, dtype=np.float64))))


def _acting_on(bodies: np.ndarray, n_bodies: int) -> tuple[np.ndarray, np.ndarray]:
    """Per body, the (connector, slot) pairs that act on it in connector order, as ``pairs[ptr[b]:ptr[b + 1]]``
    (the kernel's scatter of forces to bodies)."""
    lists: list[list[tuple[int, int]]] = [[] for _ in range(n_bodies)]
    for c in range(bodies.shape[0]):
        for s in range(bodies.shape[1]):
            if bodies[c, s] >= 0:
                lists[int(bodies[c, s])].append((c, s))
    ptr = np.zeros(n_bodies + 1, dtype=np.int64)
    ptr[1:] = np.cumsum([len(x) for x in lists])
    pairs = np.array([p for x in lists for p in x], dtype=np.int64).reshape(-1, 2)
    return ptr, pairs


# ------------------------------------------------------------------------------------------- auto
# What a run costs on either engine: gearcli.core.cost (one price per evaluation and engine, measured).
_runs = {"expected": 1, "active": 0}


def expect_runs(n: int) -> None:
    """Tell ``auto`` that this process will integrate about ``n`` more runs (a report's ladder, a sweep's
    task): the one-time cost of loading the kernel is shared by all the runs announced in the process (a
    sweep worker that gets one point per task switches once its points have added up)."""
    _runs["expected"] += max(0, int(n))


@contextmanager
def batch(n: int) -> Iterator[None]:
    """A batch of about ``n`` runs (a report's ladder, a sweep task), announced to ``auto`` (:func:`expect_runs`)."""
    expect_runs(n)
    _runs["active"] += 1
    try:
        yield
    finally:
        _runs["active"] -= 1


def load_share_s() -> float:
    """What loading the compiled engine still costs each announced run of this process (0 once loaded)."""
    return expected_load_s() / _runs["expected"]


def options(requested: str, arrays, methods: tuple[str, ...], also: tuple[str, ...] = ()) -> dict[str, dict[str, float]]:
    """Per method, the engines that may run it under ``requested`` and what loading each still costs this
    process: what ``auto``'s method choice prices (:func:`gearcli.simulate.choice.predicted_costs`). The method is
    chosen at the compiled engine's prices wherever it may run; :func:`choose` may still keep a short one-shot
    Radau run on scipy (``REFERENCE_KEEP_S``), so that the choice of the method does not depend on whether this
    process happens to have loaded the kernel."""
    out: dict[str, dict[str, float]] = {}
    compiled_ok = requested != "python" and available()
    for m in methods:
        opts = {"python": 0.0} if requested != "compiled" else {}
        if compiled_ok and not unsupported(arrays, m) and not also:
            opts["compiled"] = load_share_s()
        out[m] = opts or {"python": 0.0}
    return out


@dataclass(frozen=True)
class EngineChoice:
    engine: str  # "python" or "compiled"
    requested: str
    reason: str
    unsupported: tuple[str, ...] = ()


def choose(requested: str, arrays, method: str, nfev_estimate: float, also: tuple[str, ...] = ()) -> EngineChoice:
    """The engine of one run. ``compiled`` without numba raises :class:`~gearcli.errors.ConfigError`
    (a usage error naming the extra); a scene the kernel does not support (or with the caller's reasons
    ``also``) runs on Python with the reason.

    ``auto`` takes the compiled engine for every method it has (Radau included, one-shot runs too: its results
    agree with scipy's to the tolerance; a one-shot run of such a method only when it saves at least
    ``REFERENCE_KEEP_S``, else scipy's reference numbers) when it is installed, supports the scene, and is predicted faster
    including what loading it still costs this process (numba import and cache load, measured on the last
    load; nothing once loaded; a full compilation when nothing is cached, so that a one-shot run never waits
    for the compiler), that load shared by the runs announced with :func:`expect_runs`. The prices:
    :mod:`gearcli.core.cost`.
    """
    if requested == "python":
        return EngineChoice("python", requested, "as requested")
    have = available()
    if requested == "compiled" and not have:
        raise ConfigError(f'engine = "compiled" needs numba, the fast extra: {INSTALL_HINT}', key="simulation.engine")
    missing = tuple(unsupported(arrays, method)) + tuple(also)
    if missing:
        return EngineChoice("python", requested, "the compiled engine does not support " + "; ".join(missing),
                            missing)
    if requested == "compiled":
        return EngineChoice("compiled", requested, "as requested")
    if not have:
        return EngineChoice("python", requested, f"numba is not installed ({INSTALL_HINT} for the compiled engine)")
    python_s = predicted_wall_s("python", method, nfev_estimate)
    if "loaded" not in _state and python_s < MIN_LOAD_S / _runs["expected"]:  # not worth even a look at the cache
        return EngineChoice("python", requested, f"~{nfev_estimate:.2g} evaluations take ~{python_s:.2g} s in Python, "
                            f"less than importing numba alone (~{MIN_LOAD_S:g} s)")
    load_s = load_share_s()
    compiled_s = predicted_wall_s("compiled", method, nfev_estimate, load_s)
    if method not in BIT_IDENTICAL and _runs["active"] == 0 and python_s - compiled_s < REFERENCE_KEEP_S:
        return EngineChoice("python", requested, f"~{nfev_estimate:.2g} evaluations: the compiled {method} (which "
                            f"agrees with scipy to the tolerance, not step for step) would save less than "
                            f"{REFERENCE_KEEP_S:g} s of ~{python_s:.2g} s: scipy's, the reference")
    if compiled_s < python_s:
        return EngineChoice("compiled", requested, f"~{nfev_estimate:.2g} evaluations: ~{compiled_s:.2g} s compiled "
                            f"(load included) against ~{python_s:.2g} s in Python")
    return EngineChoice("python", requested, f"~{nfev_estimate:.2g} evaluations take ~{python_s:.2g} s in Python, less "
                        f"than loading the compiled engine (~{load_s:.2g} s)")
