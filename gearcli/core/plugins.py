"""Plug-ins of installed packages: the entry-point group ``gearcli.plugins`` (docs/plugins.md).

A package that adds a stage kind or a rating standard declares, in its ``pyproject.toml``::

    [project.entry-points."gearcli.plugins"]
    myplugin = "myplugin"              # a module: importing it registers what it provides
    # or   myplugin = "myplugin:register"   a function, called once with no arguments

gearcli loads the group once per process, and only when a design file names what no loaded code registered (a
``[[stage]] type`` or a ``[rating] standard``): a file that names only the built-in kinds and ISO 6336 never scans
the installed packages (start-up time). A plug-in that fails to load does not stop the others; what it raised is
returned, so the message that a name is unknown can say why. Imports nothing of gearcli.
"""

from __future__ import annotations

from importlib.metadata import EntryPoint, entry_points

GROUP = "gearcli.plugins"

_failures: tuple[str, ...] | None = None  # None: the group is not loaded yet


def load() -> tuple[str, ...]:
    """Load every plug-in of the group (once per process): each entry point's object is imported, and called
    with no arguments when it is a function. Returns the failures, one line each (``name (value): Error: text``)."""
    global _failures
    if _failures is None:
        _failures = ()  # set first: a plug-in that reads a design file while it loads does not load the group again
        _failures = tuple(f for f in (_load_one(ep) for ep in entry_points(group=GROUP)) if f)
    return _failures


def failures_text(failures: tuple[str, ...]) -> str:
    """The failures as the tail of an unknown-name message ("" when none)."""
    return "".join(f"; plug-in {f}" for f in failures)


def reset() -> None:
    """Forget that the group was loaded (a test that installs a plug-in after gearcli looked)."""
    global _failures
    _failures = None


def _load_one(ep: EntryPoint) -> str:
    try:
        obj = ep.load()
        if callable(obj) and not isinstance(obj, type):
            obj()
    except Exception as exc:  # any error of third-party code: reported with the name that needs it
        text = " ".join(str(exc).split())[:300]
        return f"{ep.name!r} ({ep.value}) failed to load: {type(exc).__name__}: {text}"
    return ""
