"""numba's on-disk cache held to gearcli's rules (imported with numba, by the kernel's modules only).

numba's own ``cache=True`` looks for a place to write in turn (``NUMBA_CACHE_DIR``, the source's ``__pycache__``,
``~/.cache/numba``, ...), follows symbolic links and unpickles whatever index file it finds. The kernel's functions
get this cache instead (:func:`jit`):

- one place only: the directory :func:`gearcli.engine.load` checked (owned by the user, writable by nobody else;
  :mod:`gearcli.engine.cachedir`) and set in :data:`DIR`; none set, nothing is cached (a refused directory);
- every index and data file opened without following a symbolic link, written through a private temporary file
  (``O_EXCL``, mode 0600, named with the process id so that an interrupted build's leftovers are its own);
- a file that cannot be read back (garbage, empty, truncated, a directory where a file belongs) raises
  :class:`CacheDamaged` naming it; with :data:`STRICT` (a process that only loads what a build cached) a missing
  entry does too, so that a process never compiles by surprise;
- a cached function is loaded without numba's full target refresh (which imports every numba extension, ~0.2 s;
  the compiler still does it before any compilation): only the runtime (NRT) a cached function calls;
- and without parsing its linkable IR (:class:`_Library`): numba stores, beside a function's machine code, its
  LLVM module in a form other functions can link in, and parses it on every load only to list the symbols the
  machine code defines. The entry stores that list (:meth:`_Impl.reduce`), and the module is parsed when a
  compilation first links the function in (a build, or numba compiling a signature the cache lacks), never in a
  process that only loads: 0.08 s of the 0.14 s of CPU a ``report`` of the seed spent loading its three entries.
"""

from __future__ import annotations

import contextlib
import inspect
import io
import os
import pickle
import stat
import sys
import uuid
from collections.abc import Iterator
from typing import Any

import numba
from llvmlite import binding as llvm
from numba.core import caching, compiler
from numba.core.codegen import JITCodeLibrary
from numba.core.runtime import rtsys

from gearcli.engine import cachedir, location
from gearcli.engine.cachedir import CacheDamaged

DIR: list[str] = []  # the checked cache directory of this process ([]: nothing cached)
STRICT: list[bool] = [False]  # a missing entry is damage (a loading process), not a reason to compile (a build)
DAMAGED: list[str] = []  # a build's findings: damaged entries it discarded and compiled again


class _Locator(caching._SourceFileBackedLocatorMixin, caching._CacheLocator):
    """numba's per-source-directory subdirectory (``<dir>_<sha1>``), under :data:`DIR` only."""

    def __init__(self, py_func: Any, py_file: str) -> None:
        self._py_file = py_file
        self._lineno = py_func.__code__.co_firstlineno
        self._cache_path = os.path.join(DIR[0], self.get_suitable_cache_subpath(py_file))

    def ensure_cache_path(self) -> None:
        problem = cachedir.make_private(self._cache_path)
        if problem and not STRICT[0]:  # inside the checked directory: damage (a file where it belongs), replaced
            DAMAGED.append(problem)
            cachedir.clear_entry(self._cache_path)
            problem = cachedir.make_private(self._cache_path)
        if problem:
            raise CacheDamaged(problem, (self._cache_path,))

    def get_cache_path(self) -> str:
        return self._cache_path

    @classmethod
    def from_function(cls, py_func: Any, py_file: str) -> _Locator:
        return cls(py_func, py_file)


class _Impl(caching.CompileResultCacheImpl):
    def __init__(self, py_func: Any) -> None:  # numba's, with the one locator above (never numba's fallbacks)
        self._lineno = py_func.__code__.co_firstlineno
        source = inspect.getfile(py_func)
        self._locator = _Locator(py_func, source)
        self._locator.ensure_cache_path()
        modname = os.path.splitext(os.path.basename(source))[0]
        self._filename_base = self.get_filename_base(f"{modname}.{py_func.__qualname__}", getattr(sys, "abiflags", ""))

    def reduce(self, cres: Any) -> Any:
        """numba's entry (``CompileResult._reduce``) and the symbols its machine code defines: what numba's loader
        reads off the parsed linkable module (``JitEngine._load_defined_symbols``), listed here from the same
        module, which numba's serialisation has just made."""
        payload = cres._reduce()
        if not _fast_load() or len(payload) != len(_PAYLOAD):  # another numba: its own entry, rebuilt its own way
            return _NUMBA, None, payload
        mod = cres.library._get_module_for_linking()
        defined = frozenset(gv.name for gs in (mod.functions, mod.global_variables) for gv in gs
                            if not gv.is_declaration)
        return _FORMAT, defined, payload

    def rebuild(self, target_context: Any, payload: Any) -> Any:
        """numba's ``CompileResult._rebuild``, step for step, with the library loaded by :func:`_load_library`."""
        tag, defined, entry = payload
        if tag == _NUMBA:
            return compiler.CompileResult._rebuild(target_context, *entry)
        if tag != _FORMAT:
            raise ValueError(f"an entry of another format ({tag!r})")
        libdata, fndesc, env, signature, objectmode, lifted, typeann, reload_init, referenced_envs = entry
        for fn in reload_init or ():
            fn()
        library = _load_library(target_context.codegen(), libdata, defined)
        cfunc = target_context.get_executable(library, fndesc, env)
        cres = _COMPILE_RESULT(
            target_context=target_context, typing_context=target_context.typing_context, library=library,
            environment=env, entry_point=cfunc, fndesc=fndesc, type_annotation=typeann, signature=signature,
            objectmode=objectmode, lifted=lifted, typing_error=None, call_helper=None, metadata=None,
            reload_init=reload_init, referenced_envs=referenced_envs)
        for ref in referenced_envs:
            library.codegen.set_env(ref.env_name, ref)
        return cres


_FORMAT = "gearcli-1: machine code, defined symbols, linkable IR parsed on first link"
_NUMBA = "numba: CompileResult._reduce's entry, rebuilt by CompileResult._rebuild"
_COMPILE_RESULT: Any = compiler.CompileResult  # a namedtuple numba builds from its field list: keywords, as numba's own
#: the entry ``CompileResult._reduce`` makes, in the order :meth:`_Impl.rebuild` reads it (numba 0.60 ... 0.68)
_PAYLOAD = ("libdata", "fndesc", "env", "signature", "objectmode", "lifted", "typeann", "reload_init",
            "referenced_envs")
_RESULT_FIELDS = frozenset({"target_context", "typing_context", "library", "environment", "entry_point", "fndesc",
                            "type_annotation", "signature", "objectmode", "lifted", "typing_error", "call_helper",
                            "metadata", "reload_init", "referenced_envs"})


def _fast_load() -> bool:
    """Whether this numba's internals are those :meth:`_Impl.rebuild` and :func:`_load_library` follow step for step
    (numba 0.68's); with another numba the entries are numba's own, loaded numba's way (the IR parsed on load)."""
    return (frozenset(getattr(compiler.CompileResult, "_fields", ())) == _RESULT_FIELDS
            and all(hasattr(JITCodeLibrary, name) for name in ("enable_object_caching", "_set_compiled_object",
                                                               "_finalize_final_module", "_get_module_for_linking"))
            and hasattr(compiler.CompileResult, "_rebuild"))


class _Library(JITCodeLibrary):
    """numba's library of a cached function, whose linkable module (``_shared_module``) is parsed from the stored
    bitcode the first time a compilation links the function in, not when the function is loaded."""

    _linkable: bytes | None = None

    def _get_module_for_linking(self) -> Any:
        if self._shared_module is None and self._linkable is not None:
            self._shared_module = llvm.parse_bitcode(self._linkable)
            self._linkable = None
        return super()._get_module_for_linking()


def _load_library(codegen: Any, libdata: Any, defined: frozenset[str]) -> Any:
    """numba's ``CodeLibrary._unserialize`` of an object-code entry (``serialize_using_object_code``), step for
    step, except that the linkable module is kept as bitcode (:class:`_Library`) and the symbols the machine code
    defines come from the entry instead of that module's parse."""
    name, kind, (object_code, shared_bitcode) = libdata
    if kind != "object" or codegen._library_class is not JITCodeLibrary:
        raise ValueError(f"an entry of kind {kind!r} for {type(codegen).__name__}")
    library = _Library(codegen, name)
    library.enable_object_caching()
    library._set_compiled_object(object_code)
    library._linkable = shared_bitcode
    library._finalize_final_module()
    codegen._engine._defined_symbols |= defined  # what _load_defined_symbols(parsed module) would add
    return library


def _read(path: str) -> bytes:
    """The bytes of the regular file ``path``, not through a symbolic link (FileNotFoundError when absent)."""
    fd = os.open(path, os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK)
    try:
        if not stat.S_ISREG(os.fstat(fd).st_mode):
            raise IsADirectoryError(f"{path} is not a regular file")
        with os.fdopen(os.dup(fd), "rb") as fh:
            return fh.read()
    finally:
        os.close(fd)


class _Files(caching.IndexDataCacheFile):
    """numba's index and data files, read and written without following links; unreadable ones are damage."""

    def _load_index(self) -> dict:
        try:
            raw = _read(self._index_path)
        except FileNotFoundError:
            return {}

        buf = io.BytesIO(raw)
        version = pickle.load(buf)
        if version != self._version:
            return {}
        stamp, overloads = pickle.loads(buf.read())
        if not isinstance(overloads, dict):
            raise CacheDamaged(f"{self._index_path}: not an index")
        return overloads if stamp == self._source_stamp else {}

    def load(self, key: Any) -> Any:
        name = self._load_index().get(key)
        if name is None:
            return None
        return self._load_data(name)  # a missing or unreadable data file the index names is damage

    def _load_data(self, name: str) -> Any:
        return pickle.loads(_read(self._data_path(name)))

    @contextlib.contextmanager
    def _open_for_write(self, filepath: str) -> Iterator[Any]:
        tmp = f"{filepath}.tmp.{os.getpid()}.{uuid.uuid4().hex[:8]}"
        fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_NOFOLLOW, 0o600)
        try:
            with os.fdopen(fd, "wb") as fh:
                yield fh
            cachedir.clear_entry(filepath)  # a directory where the file belongs (damage) goes first
            os.replace(tmp, filepath)
        except BaseException:
            with contextlib.suppress(OSError):
                os.unlink(tmp)
            raise


class Cache(caching.FunctionCache):
    """A per-function cache in :data:`DIR` (:mod:`numba.core.caching`'s driver with the classes above)."""

    _impl_class = _Impl

    def __init__(self, py_func: Any) -> None:  # numba's Cache.__init__ with _Files
        self._name = repr(py_func)
        self._py_func = py_func
        self._impl = self._impl_class(py_func)
        self._cache_path = self._impl.locator.get_cache_path()
        self._cache_file = _Files(cache_path=self._cache_path, filename_base=self._impl.filename_base,
                                  source_stamp=self._impl.locator.get_source_stamp())
        self.enable()

    def load_overload(self, sig: Any, target_context: Any) -> Any:
        rtsys.initialize(target_context)  # what a cached function calls (numba's refresh() is for compiling)
        try:
            try:
                data = self._load_overload(sig, target_context)
            except CacheDamaged:
                raise
            except Exception as exc:  # unpickling garbage raises anything
                raise CacheDamaged(f"{self._cache_file._index_path}: {type(exc).__name__}: {exc}",
                                   self._entry_files()) from exc
        except CacheDamaged as exc:
            if STRICT[0]:
                raise
            DAMAGED.append(str(exc))  # a build: discard this function's entries and compile it again
            self._discard()
            return None
        if data is None and STRICT[0]:
            raise CacheDamaged(f"{self._cache_file._index_path}: no entry for {self._py_func.__qualname__}{sig}",
                               self._entry_files())
        return data

    def _entry_files(self) -> tuple[str, ...]:
        """This function's index and data files."""
        base = self._impl.filename_base + "."
        try:
            names = os.listdir(self._cache_path)
        except OSError:
            return ()
        return tuple(os.path.join(self._cache_path, n) for n in names if n.startswith(base))

    def _discard(self) -> None:
        cachedir.discard_entry(self._entry_files())


_REFCOUNT: dict[bool, dict[str, Any]] = {b: {"_nrt": b} for b in (False, True)}  # numba's (internal) NRT switch


def jit(fn: Any) -> Any:
    """``numba.njit`` with :class:`Cache` (when :data:`DIR` is set) and the kernel's options, for a function that
    allocates no array (the element laws, the right-hand side, the steps): compiled without numba's reference
    counting (``_nrt=False``). numba counts a reference each time a function receives an array or takes a view
    of one (an atomic increment and decrement, and an opaque call that keeps LLVM from optimising across it):
    on the seed that was 85 % of a right-hand side evaluation (6.9 us against 0.39 us without). Such a function
    borrows the arrays its caller owns; an allocation inside one fails to compile (numba: "Only accept returning
    of array passed into the function as argument"), never silently."""
    return _cached(numba.njit(error_model="numpy", nogil=True, **_REFCOUNT[False])(fn))


def jit_alloc(fn: Any) -> Any:
    """:func:`jit` for a function that allocates arrays (a driver's scratch, its results): reference counted."""
    return _cached(numba.njit(error_model="numpy", nogil=True, **_REFCOUNT[True])(fn))


def _cached(dispatcher: Any) -> Any:
    if DIR and hasattr(dispatcher, "_cache"):  # NUMBA_DISABLE_JIT gives the Python function back
        dispatcher._cache = Cache(dispatcher.py_func)
    return dispatcher


def _default() -> None:
    """A direct ``import gearcli.engine.kernel`` (tests do it) binds the kernel to the user's cache when it is trusted
    (numba then compiles what is missing in that process, as it always did); :func:`gearcli.engine.load` sets
    :data:`DIR` itself before it imports the kernel."""
    if not DIR and location.cache_problem() is None:
        DIR.append(str(location.cache_dir()))


_default()
