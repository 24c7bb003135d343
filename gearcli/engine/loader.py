"""Where the compiled kernel is cached, how a process loads it, and how a first use builds it.

The cache: ``$XDG_CACHE_HOME/gearcli/numba``, else ``~/.cache/gearcli/numba``, else ``$TMPDIR/gearcli-<uid>/numba``
(:func:`cache_choice`), one subdirectory per kernel source and numba version (:func:`cache_dir`). Every directory
gearcli creates there is mode 0700; one found already there is used only when it is the user's own and writable
by nobody else (:mod:`gearcli.engine.cachedir`). A refused directory is named in one line and the run compiles
into a private temporary directory instead, removed once the kernel is loaded (nothing is cached).

A process loads the kernel once (:func:`load`): numba's import and the kernel module's (its ~100 dispatchers,
each bound to the checked directory), then each integration entry the first time a run needs it (:func:`entry`),
the cached machine code only (no type inference, no numba target refresh). Nothing cached yet: the kernel is
compiled first in a child process (:mod:`gearcli.engine.builder`), shown as a step with its measured time. A
damaged cache (an entry that cannot be read back) is named in one line, discarded and rebuilt.

Loading runs with signals held back (:func:`gearcli.core.signals.deferred`): a Ctrl-C arriving inside numba's
loader is acted on when it returns (a fraction of a second), never inside it.
"""

from __future__ import annotations

import importlib.util
import os
import sys
import tempfile
import threading
import time
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import numpy as np

from gearcli.core import announce, signals
from gearcli.core.announce import LineReporter
from gearcli.core.cost import COMPILE_S, DEFAULT_LOAD_S
from gearcli.core.records import record
from gearcli.engine import builder, cachedir
from gearcli.engine.cachedir import CacheDamaged
from gearcli.engine.location import (  # noqa: F401 - the package's interface (gearcli.engine re-exports them)
    FRESH,
    _source_key,  # the cache tests name the key directory
    cache_choice,
    cache_dir,
    cache_problem,
    cache_root,
)
from gearcli.engine.packing import Model, _acting_on
from gearcli.errors import ConfigError, SimulationError
from gearcli.model import elements, outputs
from gearcli.model.elements import machine

ENTRIES = {"DOP853": "dop853", "RK45": "rk45", "Radau": "radau"}

_state: dict = {}
#: held while a thread loads the kernel, warms an entry or repairs the cache: loading pops the kernel's modules from
#: ``sys.modules`` and imports them anew (:func:`import_kernel`), so two threads of one process loading at once broke
#: each other's import (``KeyError: 'gearcli.engine.kernel'``); re-entrant (a repair loads again)
_LOCK = threading.RLock()


def ready(directory: Path) -> bool:
    """Whether a build finished in ``directory`` (its ``ready.json``, read without following a link)."""
    return isinstance(cachedir.read_json(directory / "ready.json"), dict)


def mark_ready(directory: Path, compile_s: float) -> None:
    cachedir.write_json(directory / "ready.json", {"compile_s": compile_s})


def _ready_here(cdir: Path | None = None) -> bool:
    """The user's cache (``cdir``: :func:`cache_dir`, when the caller has it) is ready and trusted (without
    creating anything when nothing is there yet)."""
    cdir = cache_dir() if cdir is None else cdir
    return cdir.is_dir() and ready(cdir) and cache_problem() is None


# ------------------------------------------------------------------------------------------- reporting
def quiet_compilation() -> None:
    """This process does not announce a compilation (a sweep's pool worker: its parent announced it once)."""
    _state["quiet"] = True


def _reporter(quiet: bool) -> Any:
    if quiet or _state.get("quiet"):
        return LineReporter(quiet=True)
    return announce.build_reporter() or LineReporter()


def _say(text: str, quiet: bool) -> None:
    """One line on stderr (the build's reporter's way: a quiet one says nothing)."""
    reporter = announce.build_reporter()
    if quiet or _state.get("quiet") or getattr(reporter, "quiet", False):
        return
    print(f"gearcli: {text}", file=sys.stderr, flush=True)


# ------------------------------------------------------------------------------------------- loading
@record
class Loaded:
    """The compiled kernel as loaded in this process, and what loading it cost."""

    kernel: Any  # the gearcli.engine.kernel module
    load_s: float  # numba import + the kernel module's (and a build's, when this process built it)
    compiled: bool  # compiled now (no cache)
    build_s: float = 0.0  # the build's share of load_s


@contextmanager
def _strict() -> Iterator[None]:
    """Inside, an entry missing from the cache is damage (this process loads what a build cached, it never
    compiles by surprise); outside, a call with an unforeseen signature compiles as numba does."""
    from gearcli.engine import numba_cache  # lazy: numba (numba_cache imports it), the optional fast extra

    numba_cache.STRICT[0] = True
    try:
        yield
    finally:
        numba_cache.STRICT[0] = False


def import_kernel(directory: Path, strict: bool) -> tuple[Any, Any]:
    """Import numba and the kernel module bound to ``directory`` (a fresh import: a repaired cache gets new
    dispatchers); (the module, a function giving the damaged entries a build discarded)."""
    from gearcli.engine import numba_cache  # lazy: numba (numba_cache imports it), the optional fast extra

    numba_cache.DIR[:] = [str(directory)]
    numba_cache.STRICT[0] = strict
    numba_cache.DAMAGED.clear()
    package = sys.modules[__name__.rpartition(".")[0]]  # gearcli.engine, whose import runs this module's
    for name in FRESH:  # the modules holding dispatchers: imported anew, bound to ``directory``
        sys.modules.pop(name, None)
        if name.startswith(package.__name__ + ".") and hasattr(package, name.rpartition(".")[2]):
            delattr(package, name.rpartition(".")[2])
    kernel = importlib.import_module("gearcli.engine.kernel")  # numba: the kernel compiles or loads its cache
    return kernel, lambda: list(numba_cache.DAMAGED)


def load(quiet: bool = False) -> Loaded:
    """Import numba and the kernel, building the cache first when nothing is cached (a step with its measured
    time on stderr, ``quiet`` silences it); once per process, whichever of its threads asks first (the others wait
    for it: :data:`_LOCK`)."""
    found = _state.get("loaded")
    if found is not None:
        return found
    with _LOCK:
        found = _state.get("loaded")
        return found if found is not None else _load(quiet)


def _load(quiet: bool) -> Loaded:
    t0 = time.perf_counter()
    problem = cache_problem()
    private = None
    if problem:
        private = Path(tempfile.mkdtemp(prefix="gearcli-engine-"))
        _say(f"not using the engine cache: {problem}; compiling into a private temporary directory for this run "
             "(make that directory yours with mode 0700, or remove it, to cache again)", quiet)
    cdir = private or cache_dir()
    try:
        kernel, built = _load_from(cdir, quiet)
        build_s = _state.pop("build_s", 0.0)
        if private is not None:
            with signals.deferred(), _strict():
                warm_up(kernel)  # everything, before the private directory goes
    finally:
        if private is not None:
            cachedir.discard(private)
    _state["loaded"] = Loaded(kernel, time.perf_counter() - t0, built, build_s)
    outputs.use_compiled(kernel)  # the model's sampled outputs run the compiled laws from now on
    _state["dir"] = None if private else cdir
    return _state["loaded"]


def _load_from(cdir: Path, quiet: bool) -> tuple[Any, bool]:
    """The kernel module loaded from ``cdir`` (built first when not ready; a damaged entry met while importing is
    named, discarded and rebuilt)."""
    built = False
    for attempt in range(3):
        if not ready(cdir):
            if os.path.lexists(cdir / "ready.json"):
                _say(f"the engine cache {cdir} is damaged (ready.json is not a file); building it again", quiet)
            _build(cdir, quiet)
            built = True
        try:
            with signals.deferred(), _strict():
                kernel, _ = import_kernel(cdir, strict=True)
            return kernel, built
        except CacheDamaged as exc:
            if attempt == 2:
                raise
            _discard(exc, cdir, quiet)
    raise AssertionError("unreachable")


def _build(cdir: Path, quiet: bool) -> None:
    why = cache_choice()[1]  # $XDG_CACHE_HOME (or ~/.cache) cannot hold the cache: the build says where it goes
    if why and cdir == cache_dir():
        _say(f"{why}; the integration engine is cached in {cache_root()} instead", quiet)
    reporter = _reporter(quiet)
    reporter.reason = _state.pop("why_build", reporter.reason)  # not its first use: --force, or a damaged cache
    try:
        _state["build_s"] = _state.get("build_s", 0.0) + builder.run(cdir, reporter)
    except builder.BuildFailed as exc:
        raise SimulationError(str(exc)) from None


def _discard(exc: CacheDamaged, cdir: Path, quiet: bool) -> None:
    """Name a damaged entry in one line and remove it (the next build compiles it again)."""
    _say(f"the engine cache {cdir} is damaged ({_short(str(exc), cdir)}); discarded, building it again", quiet)
    _state["why_build"] = "again, its cache was damaged"
    if exc.entry:
        cachedir.discard_entry(exc.entry)
    else:
        cachedir.discard(cdir)
        cachedir.make_private(cdir)
    cachedir.discard_entry((str(cdir / "ready.json"),))


def _repair(exc: CacheDamaged) -> None:
    """A damaged entry met after the kernel module was imported: named, discarded, rebuilt; the kernel module is
    imported anew (the old dispatchers remember the failure)."""
    loaded = _state.pop("loaded")
    cdir = _state.get("dir")
    if cdir is None:  # the private directory of a refused cache is gone: nothing to repair there
        raise exc
    _discard(exc, cdir, False)
    kernel, _ = _load_from(cdir, False)
    _state["loaded"] = Loaded(kernel, loaded.load_s, True, _state.pop("build_s", 0.0))
    outputs.use_compiled(kernel)  # the kernel module imported anew: its dispatchers for the outputs too


def _short(text: str, cdir: Path) -> str:
    text = text.replace(str(cdir) + os.sep, "")
    return text if len(text) <= 160 else text[:157] + "..."


def entry(method: str) -> tuple[Any, float]:
    """The kernel's integration function for ``method`` (loading it from the cache the first time, with signals
    held back) and the seconds this call spent loading it (0 once loaded)."""
    loaded = load()
    name = ENTRIES[method]
    warm = _state.setdefault("warm", {})
    if name in warm:
        return getattr(loaded.kernel, name), 0.0
    with _LOCK:  # one thread warms it (a repair imports the kernel anew), the others then find it warm
        if name in warm:
            return getattr(load().kernel, name), 0.0
        return _warmed(name, loaded)


def _warmed(name: str, loaded: Loaded) -> tuple[Any, float]:
    """:func:`entry`'s first load of the entry ``name`` (under :data:`_LOCK`; ``loaded``: the kernel as it found it)."""
    warm = _state["warm"]
    t0 = time.perf_counter()
    for attempt in range(3):  # another process sharing the cache may be repairing it too: a few rounds settle it
        try:
            with signals.deferred(), _strict():
                _warm_entry(load().kernel, name)
            break
        except CacheDamaged as exc:  # the entry's files: named, discarded, rebuilt (an interruptible build), anew
            if attempt == 2:
                raise
            _repair(exc)
    spent = time.perf_counter() - t0
    warm[name] = spent
    if len(warm) == 1 and _state.get("dir") is not None and not loaded.compiled:
        cachedir.write_json(_state["dir"] / "load_time.json", {"load_s": loaded.load_s + spent})
    return getattr(loaded.kernel, name), spent


def point_functions() -> tuple[Any, Any]:
    """The kernel's ``evaluate(model, t, y)`` and ``evaluate_jacobian(model, t, y)`` (one right-hand side, one
    Jacobian at a state: the equilibrium's Newton), loaded from the cache the first time as :func:`entry` loads an
    integration entry."""
    warm = _state.setdefault("warm", {})
    if "evaluate" not in warm:
        with _LOCK:
            if "evaluate" not in warm:
                _warm_point_functions(warm)
    loaded = load()
    return loaded.kernel.evaluate, loaded.kernel.evaluate_jacobian


def _warm_point_functions(warm: dict) -> None:
    """:func:`point_functions`' first load (under :data:`_LOCK`)."""
    t0 = time.perf_counter()
    for attempt in range(3):
        try:
            with signals.deferred(), _strict():
                model, y0, _, _, _ = _tiny_args()
                kernel = load().kernel  # the kernel anew after a repair
                kernel.evaluate(model, 0.0, y0)
                kernel.evaluate_jacobian(model, 0.0, y0)
            break
        except CacheDamaged as exc:
            if attempt == 2:
                raise
            _repair(exc)
    warm["evaluate"] = time.perf_counter() - t0


def _warm_entry(kernel: Any, name: str) -> None:
    """Load one integration entry (and the output channels' and window statistics' functions, which every run's
    results call)."""
    model, y0, t_eval, tol, wpar = _tiny_args()
    getattr(kernel, name)(model, y0, t_eval, np.array([1e-3]), tol, tol, np.int64(100), np.int64(16), wpar,
                          np.empty(0))
    for c in range(2):
        kernel.connector_series(model.kind[c], model.param[c], np.zeros(2), np.zeros(2), np.zeros(2), np.zeros(2),
                                np.int64(0), np.int64(8))
    kernel.connectors_series(model.kind, model.param, model.bodies, model.levers, np.zeros(2),
                             np.zeros(2, dtype=np.int64), np.arange(2, dtype=np.int64), np.zeros((3, 2)),
                             np.zeros((3, 2)), np.zeros((1, 1)), np.int64(0), np.full(2, 8, dtype=np.int64),
                             np.int64(3))
    kernel.window_statistics(np.zeros((5, 2)), np.zeros((1, 2)), np.arange(2.0), False, np.ones(1))


@record
class Built:
    """What ``gearcli engine build`` did: where the cache is, the build's time (0: it was there) and what loading the
    kernel then cost this process (numba import, the kernel module, the DOP853 entry)."""

    directory: Path | None  # None: the cache was refused (the reason in ``refused``)
    build_s: float
    load_s: float
    refused: str | None


def build(force: bool = False, quiet: bool = False) -> Built:
    """Compile the kernel into the cache (``force``: discard what is there first) and load it as a run would."""
    if not available():
        raise ConfigError("the compiled engine needs numba, the fast extra: pip install 'gearcli[fast]'")
    if (why := import_problem()) is not None:
        raise ConfigError(f"the compiled engine needs numba, the fast extra, and numba is installed but cannot be "
                          f"imported ({why}): pip install --force-reinstall 'gearcli[fast]'")
    if "loaded" in _state:
        raise RuntimeError("build() runs in a process that has not loaded the kernel")
    problem = cache_problem()
    if force:
        _state["why_build"] = "again, as --force asked"
    if force and problem is None:
        cachedir.discard(cache_dir())
        cachedir.make_private(cache_dir())
    loaded = load(quiet=quiet)
    _, entry_s = entry("DOP853")
    return Built(None if problem else cache_dir(), loaded.build_s, loaded.load_s - loaded.build_s + entry_s, problem)


def available() -> bool:
    """Whether numba (the ``fast`` extra) is installed."""
    if "numba" in sys.modules:
        return sys.modules["numba"] is not None
    return importlib.util.find_spec("numba") is not None


def import_problem() -> str | None:
    """Why numba, though installed, cannot be imported here (a numba built for another numpy, a broken install):
    one line, or None when it imports. Imports numba (once per process): called only where a run is about to use
    the compiled engine, which imports it anyway.

    The import runs with signals held back (:func:`gearcli.core.signals.deferred`, a fraction of a second; a signal
    is acted on once it returns): numba's C extension ``numba._dispatcher`` imports ``numba._devicearray`` from its
    initialisation, and a KeyboardInterrupt raised there was printed by the extension (``PyErr_Print``: a
    traceback ending in ``_find_and_load`` on the user's terminal) and turned into "ImportError: numba._devicearray
    failed to import", a refusal of the compiled engine, or for ``engine = "auto"`` a run that went on in Python
    with the Ctrl-C dropped."""
    if "import_problem" not in _state:
        try:
            with signals.deferred():
                importlib.import_module("numba")
            _state["import_problem"] = None
        except Exception as exc:  # noqa: BLE001 - whatever numba's import raises, the engine cannot run
            _state["import_problem"] = f"{type(exc).__name__}: {exc}".splitlines()[0]
    return _state["import_problem"]


def loaded_kernel() -> Any:
    """The kernel module when this process has loaded it, else None (never loads it)."""
    loaded = _state.get("loaded")
    return loaded.kernel if loaded is not None else None


def compilation_pending() -> str | None:
    """The one-line notice for a parent whose workers may compile the kernel (numba installed, nothing cached);
    None when nothing will be compiled."""
    if importlib.util.find_spec("numba") is None or _ready_here():
        return None
    return (f"the integration engine is not compiled yet: a sweep worker that needs it will compile the integration "
            f"engine first (once, {_cache_words()}; `gearcli engine build` does it ahead, with progress)")


def _cache_words() -> str:
    cdir = cache_dir()
    why = cache_choice()[1]
    return f"cached in {cdir}" + (f": {why}, using this one instead" if why else "")


def expected_load_s() -> float:
    """What loading the kernel will cost this process: 0 when loaded, the last measured load time when
    cached, a compilation's when not."""
    if "loaded" in _state:
        return 0.0

    cdir = cache_dir()  # its key hashes the kernel's sources: computed once here
    if not _ready_here(cdir):
        return COMPILE_S
    doc = cachedir.read_json(cdir / "load_time.json")
    try:
        return float(doc["load_s"])
    except (TypeError, KeyError, ValueError):
        return DEFAULT_LOAD_S


def cached_or_loaded() -> bool:
    """Whether this process has the kernel loaded or can load it from the cache without compiling."""
    return "loaded" in _state or _ready_here(cache_dir())


# ------------------------------------------------------------------------------------------- warm-up
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
    return Model(np.array([elements.KIND_MESH, elements.KIND_SPRING], dtype=np.int64), bodies, levers, param,
                 np.array([1.0, 2.0, 3.0]), np.array([0, 2, -1, 4, 0, 0, 7, 4, 5, 6, -1], dtype=np.int64),
                 np.array([10.0, 0.01, 5.0, 0.01, 0.0, 0.0]), np.array([0.01, 2.0]), np.array([0.01, 5.0]),
                 np.array([-1, 0, 1], dtype=np.int64), *_acting_on(bodies, 3), np.zeros(machine.M_TAB),
                 np.zeros(machine.L_TAB), np.zeros((0, 0)), np.full((2, 2 * elements.MAX_BODIES), -1, dtype=np.int64),
                 np.zeros((2, 4 * elements.MAX_BODIES)))


def _tiny_args() -> tuple:
    return _tiny_model(), np.zeros(7), np.array([0.0, 1e-3]), np.full(7, 1e-6), np.array([0.0, 0.0, 1.0, 0.1, 0.0])


def warm_up(kernel: Any) -> None:
    """Compile (a build) or load every entry of the kernel."""
    model, y0, _, _, _ = _tiny_args()
    for name in ENTRIES.values():
        _warm_entry(kernel, name)
    kernel.evaluate(model, 0.0, y0)
    kernel.evaluate_many(model, 0.0, y0, np.int64(1))
    kernel.evaluate_jacobian(model, 0.0, y0)
