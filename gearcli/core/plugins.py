"""Plug-ins of installed packages: the entry-point group ``gearcli.plugins`` (docs/plugins.md).

A package that adds a stage kind or a rating standard declares, in its ``pyproject.toml``::

    [project.entry-points."gearcli.plugins"]
    myplugin = "myplugin"              # a module: importing it registers what it provides
    # or   myplugin = "myplugin:register"   a function, called once with no arguments

gearcli loads the group once per process, and only when a design file names what no loaded code registered (a
``[[stage]] type`` or a ``[rating] standard``): a file that names only the built-in kinds and ISO 6336 never scans
the installed packages (start-up time). A plug-in that fails to load does not stop the others; what it raised is
returned, so the message that a name is unknown can say why. Imports nothing of gearcli.

Who registered each name is recorded (:func:`claim`, called by the registries of stage kinds and rating
standards): a name another registrant holds, or a name built into gearcli, is refused with a :class:`NameConflict`
naming both registrants, which ends the load (it is no failure of one plug-in the others could do without: which of
the two a file would get is undecidable).
"""

from __future__ import annotations

import sys
from collections.abc import Callable, Collection
from importlib.metadata import EntryPoint, entry_points
from types import FrameType

GROUP = "gearcli.plugins"
BUILT_IN = "gearcli (built-in)"

_failures: tuple[str, ...] | None = None  # None: the group is not loaded yet
_conflict: Exception | None = None  # the NameConflict that ended the load, raised again on every load()
_loading: EntryPoint | None = None  # the entry point being loaded: the registrant of what registers meanwhile
_group: dict[str, EntryPoint] = {}  # the group's entry points by their top-level package, while it loads
_owners: dict[tuple[str, str, str], tuple[str, str]] = {}  # (what, name, part) -> (identity, label)
#: the registries' withdrawals, each given the (what, name, part) a plug-in that failed to load had registered
_undo: list[Callable[[list[tuple[str, str, str]]], None]] = []


class NameConflict(Exception):  # noqa: N818 - a marker: gearcli.errors.PluginConflict is the error raised
    """A registration refused: the name is another registrant's or gearcli's own (docs/plugins.md)."""


def claim(what: str, name: str, implementation: object, *, built_in: Collection[str], part: str = "") -> str | None:
    """Record the registrant of ``name`` (``what``: "rating standard", "stage type"; ``part``: a stage type's facet)
    and return None, or return why the registration is refused (and record nothing): ``name`` is built into gearcli
    and the registrant is not gearcli, or another registrant holds it. The registrant is gearcli for its own
    implementation of a built-in name, else the entry point being loaded (the group's entry point of the calling
    code's package when that is another one: a plug-in's module imported by the plug-in loading registers as its
    own), else the implementation's top-level package (a script or a test registering directly); the same
    registrant may register a name again (it replaces its own)."""
    module = origin(implementation)
    top = module.split(".")[0]
    if top == "gearcli" and name in built_in:
        who = ("gearcli", BUILT_IN)
    elif _loading is not None:
        caller = _caller_package()  # another plug-in's module, imported by the one loading, registers as its own
        ep = _loading if caller == _package(_loading) else _group.get(caller, _loading)
        who = (_package(ep), f"plug-in {ep.name!r} ({ep.value})")
    else:
        who = (top, f"module {module!r}")
    label = f'{what} "{name}"' + (f" (its {part} facet)" if part else "")
    if name in built_in and who[0] != "gearcli":
        return (f"{who[1]} registers {label}, a name built into gearcli: a plug-in cannot replace a built-in "
                f"{what}; give it a name of its own (docs/plugins.md)")
    held = _owners.get((what, name, part))
    if held is not None and held[0] != who[0]:
        return (f"{label} is registered twice, by {held[1]} and by {who[1]}: a name selects one; uninstall one of "
                "them (docs/plugins.md)")
    _owners[(what, name, part)] = who
    return None


def _package(ep: EntryPoint) -> str:
    """The top-level package of an entry point's object."""
    return ep.value.split(":")[0].split(".")[0].strip()


def _caller_package() -> str:
    """The top-level package of the code that called gearcli's registration: the first frame outside gearcli and
    the import machinery (a plug-in's ``register``, or the body of a module registering on import)."""
    frame: FrameType | None = sys._getframe(1)
    while frame is not None:
        top = str(frame.f_globals.get("__name__", "")).split(".")[0]
        if top not in ("gearcli", "importlib", "_frozen_importlib", "_frozen_importlib_external"):
            return top
        frame = frame.f_back
    return ""


def origin(implementation: object) -> str:
    """The module an implementation (an instance, or a class given where an instance belongs) comes from."""
    return str((implementation if isinstance(implementation, type) else type(implementation)).__module__)


def on_failure(undo: Callable[[list[tuple[str, str, str]]], None]) -> None:
    """Have ``undo`` withdraw, from its registry, what a plug-in that then failed to load had registered (each
    registry of names calls it once, when imported): a failed plug-in provides nothing, so a file naming its names
    gets the unknown-name message that says which plug-in failed and what it raised (docs/plugins.md)."""
    _undo.append(undo)


def release(what: str, name: str, part: str = "") -> None:
    """Forget the registrant of ``name`` (its registration withdrawn)."""
    _owners.pop((what, name, part), None)


def load() -> tuple[str, ...]:
    """Load every plug-in of the group (once per process): each entry point's object is imported, and called
    with no arguments when it is a function. Returns the failures, one line each (``name (value): Error: text``)."""
    global _failures, _conflict
    if _conflict is not None:
        raise _conflict
    if _failures is None:
        _failures = ()  # set first: a plug-in that reads a design file while it loads does not load the group again
        group = tuple(entry_points(group=GROUP))
        _group.update((_package(ep), ep) for ep in group)
        try:
            _failures = tuple(f for f in (_load_one(ep) for ep in group) if f)
        except NameConflict as exc:  # two registrants of one name: no plug-in's name can be trusted to mean one
            _conflict = exc
            raise
        finally:
            _group.clear()
    return _failures


def failures_text(failures: tuple[str, ...]) -> str:
    """The failures as the tail of an unknown-name message ("" when none)."""
    return "".join(f"; plug-in {f}" for f in failures)


def reset() -> None:
    """Forget that the group was loaded (a test that installs a plug-in after gearcli looked)."""
    global _failures, _conflict
    _failures = _conflict = None


def _load_one(ep: EntryPoint) -> str:
    global _loading
    _loading = ep
    before = dict(_owners)
    try:
        obj = ep.load()
        if callable(obj) and not isinstance(obj, type):
            obj()
    except NameConflict:  # not this plug-in's failure alone: the load ends (module text)
        raise
    except (Exception, SystemExit) as exc:  # any error of third-party code (its sys.exit() too: errors.PLUGIN_FAULTS),
        # reported with the name that needs it
        text = " ".join(str(exc).split())[:300]
        _withdraw_own(ep, before)
        return f"{ep.name!r} ({ep.value}) failed to load: {type(exc).__name__}: {text}"
    finally:
        _loading = None
    return ""


def _withdraw_own(ep: EntryPoint, before: dict[tuple[str, str, str], tuple[str, str]]) -> None:
    """Withdraw what entry point ``ep`` registered before it failed (a kind's table and design facet, say, and not
    its model facet: a file naming the kind met "no model facet registered" and never the plug-in's error)."""
    mine = [key for key, who in _owners.items() if who[0] == _package(ep) and before.get(key) != who]
    for undo in _undo:
        undo(mine)
    for key in mine:
        release(*key)
