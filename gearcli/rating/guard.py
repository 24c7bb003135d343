"""A rating standard registered from outside gearcli, held to its protocol (docs/plugins.md).

The registry keeps a plug-in standard behind :class:`Guarded`: every call goes through, and what the standard
raises (other than gearcli's own errors, which keep their message and exit code) or returns outside the protocol
(:class:`~gearcli.rating.standard.RatingStandard`) is a :class:`~gearcli.errors.PluginError` naming the standard,
the call and what is wrong, never a traceback or an internal error far from its cause. ISO 6336 is not wrapped.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable, Mapping, Sequence
from typing import TYPE_CHECKING, Any, NoReturn

from gearcli.core import plugins
from gearcli.core.text import shorten
from gearcli.diagnostics import Diagnostic
from gearcli.errors import PLUGIN_FAULTS, GearcliError, PluginError
from gearcli.rating.sn import SNCurve, curve_problem
from gearcli.rating.standard import MODES
from gearcli.stages import kinds

if TYPE_CHECKING:
    from gearcli.rating.standard import RatingStandard


class Guarded:
    """``std`` with its calls checked; ``name``, ``title`` and any further attribute are the standard's own."""

    def __init__(self, std: RatingStandard):
        self.std = std
        self.name = std.name
        self.title = std.title

    def __getattr__(self, attr: str) -> Any:  # rate_at_force (optional) and anything else a standard offers
        if attr.startswith("__") or attr == "std":  # copy and pickle ask before __init__ ran
            raise AttributeError(attr)
        value = getattr(self.std, attr)
        if attr == "rate_at_force" and callable(value):
            return lambda cfg, stage, ratio: self._mesh(self._call(attr, value, cfg, stage, ratio), attr, None)
        if attr == "rate_stage_at_force" and callable(value):
            return lambda cfg, stage, ratio: self._stage_at_force(self._call(attr, value, cfg, stage, ratio), stage)
        return value

    def _stage_at_force(self, out: Any, given: Any) -> Any:
        """``rate_stage_at_force``'s stage: None, or the given stage's type with its ratings rated meshes."""
        if out is None:
            return out
        return self._stages("rate_stage_at_force", ((out,), ()), (given,))[0][0]

    def check_inputs(self, cfg: Any) -> None:
        self._call("check_inputs", self._method("check_inputs"), cfg)

    def rate_design(self, cfg: Any, stages: tuple) -> tuple[tuple, tuple[Diagnostic, ...]]:
        out = self._call("rate_design", self._method("rate_design"), cfg, stages)
        rated, diags = self._stages("rate_design", out, stages)
        return rated, tuple(diags)

    def rate_simulation(self, cfg: Any, design: Any, stages: Sequence) -> tuple[tuple, list[Diagnostic]]:
        out = self._call("rate_simulation", self._method("rate_simulation"), cfg, design, stages)
        rated, diags = self._stages("rate_simulation", out, stages)
        return rated, list(diags)

    def sn_curve(self, cfg: Any, member: Any, treatment: str, mode: str, variant: str) -> SNCurve:
        curve = self._call("sn_curve", self._method("sn_curve"), cfg, member, treatment, mode, variant)
        if not isinstance(curve, SNCurve):
            self._fail("sn_curve", f"returned {type(curve).__name__}, not a gearcli.rating.sn.SNCurve")
        why = curve_problem(curve)
        if why is not None:  # else life's arithmetic fails far from it (a division by zero, a NaN in the JSON)
            self._fail("sn_curve", f"returned the {mode} curve {shorten(repr(curve.nodes), 120)} whose {why}")
        return curve

    def curve_name(self, mode: str) -> str:
        return self._text("curve_name", self._call("curve_name", self._method("curve_name"), mode))

    def table_rows(self, ratings: Sequence, *, shared: bool) -> list[tuple[str, list[str]]]:
        method = self._method("table_rows")
        rows = self._call("table_rows", lambda: method(ratings, shared=shared))
        ok = isinstance(rows, (list, tuple)) and all(
            isinstance(r, (list, tuple)) and len(r) == 2 and isinstance(r[0], str)
            and isinstance(r[1], (list, tuple)) and len(r[1]) == len(ratings) and all(isinstance(c, str) for c in r[1])
            for r in rows)
        if not ok:
            self._fail("table_rows", f"must return a list of (label, [one text per rated mesh ({len(ratings)})]) "
                       f"rows, got {shorten(repr(rows), 200)}")
        return [(label, list(cells)) for label, cells in rows]

    # ------------------------------------------------------------------------------------------- the checks
    def _call(self, what: str, fn: Callable, *args: Any) -> Any:
        if isinstance(self.std, type):  # the class registered where its instance belongs: every call would fail
            self._fail(what, f"cannot be called: the standard registered is the class {self.std.__name__}, not an "
                       f"instance of it (register({self.std.__name__}()))")
        try:
            return fn(*args)
        except GearcliError:
            raise
        except PLUGIN_FAULTS as exc:  # third-party code: named, with what it raised
            self._fail(what, f"raised {type(exc).__name__}: {shorten(' '.join(str(exc).split()), 300)}")

    def _method(self, what: str) -> Callable:
        """The standard's method ``what``, or a PluginError: it is missing (the protocol's every method is asked)."""
        method = getattr(self.std, what, None)
        if method is None or not callable(method):
            self._fail(what, "is missing" if method is None else f"is {type(method).__name__}, not a method")
        return method

    def _fail(self, what: str, text: str) -> NoReturn:
        raise PluginError(f'rating standard "{self.name}" ({plugins.origin(self.std)}): {what} {text} '
                          "(docs/plugins.md, the rating standard's protocol)")

    def _text(self, what: str, value: object) -> str:
        if not isinstance(value, str):
            self._fail(what, f"returned {type(value).__name__}, not a str")
        return str(value)

    def _stages(self, what: str, out: Any, given: Sequence) -> tuple[tuple, list]:
        if not (isinstance(out, (list, tuple)) and len(out) == 2 and isinstance(out[0], (list, tuple))
                and isinstance(out[1], (list, tuple))):
            self._fail(what, f"must return (stages, warnings), got {shorten(repr(out), 200)}")
        rated: Sequence[Any] = out[0]
        diags: Sequence[Any] = out[1]
        if len(rated) != len(given):
            self._fail(what, f"returned {len(rated)} stages for {len(given)}")
        for k, (new, old) in enumerate(zip(rated, given, strict=True)):
            if type(new) is not type(old):
                self._fail(what, f"returned stage {k + 1} as {type(new).__name__}, not the {type(old).__name__} it "
                           "was given (dataclasses.replace(stage, rating=...))")
            self._mesh(getattr(new, "rating", None), what, k)
            for further in _further_ratings(new):  # a planetary stage's planet–ring mesh
                self._mesh(further, what, k, "planet–ring rating")
        for d in diags:
            if not isinstance(d, Diagnostic):
                self._fail(what, f"returned the warning {shorten(repr(d), 100)}, not a gearcli.diagnostics.Diagnostic "
                           "(gearcli.diagnostics.warning(code, message))")
        return tuple(rated), list(diags)

    def _mesh(self, rating: object, what: str, k: int | None, label: str = "rating") -> object:
        """A rated mesh as the layers above read it (``gearcli.rating.RatedMesh``); None is "not rated"."""
        if rating is None:
            return rating
        where = f"stage {k + 1}'s {label}" if k is not None else f"the {label}"
        if not dataclasses.is_dataclass(rating) or isinstance(rating, type):
            self._fail(what, f"returned {where} as {type(rating).__name__}: a rated mesh is a dataclass (its JSON "
                       "is its fields)")
        title = getattr(rating, "standard", None)
        if title != self.title:
            self._fail(what, f"returned {where} titled {title!r}: its standard must be the standard's title "
                       f"{self.title!r} (the table and life find the standard by it)")
        self._number(what, f"{where}: K_v", getattr(rating, "K_v", None))
        for member in ("pinion", "gear"):
            m = getattr(rating, member, None)
            if m is None:
                self._fail(what, f"returned {where} without its {member}")
            self._number(what, f"{where}: {member}.load_cycles", getattr(m, "load_cycles", None))
            for mode in MODES:
                for fn in ("safety", "stress_MPa"):
                    got = self._call(f"{what}: {member}.{fn}", getattr(m, fn, None) or _missing(fn), mode)
                    self._number(what, f"{where}: {member}.{fn}({mode!r})", got)
        table = self._call(f"{what}: factor_table", getattr(rating, "factor_table", None) or _missing("factor_table"))
        if not isinstance(table, Mapping) or not all(isinstance(v, (int, float, str)) for v in table.values()):
            self._fail(what, f"returned {where} whose factor_table() is not a mapping of names to numbers or texts")
        return rating

    def _number(self, what: str, name: str, value: object) -> None:
        if isinstance(value, bool) or not isinstance(value, (int, float)) or math.isnan(value) or value < 0:
            self._fail(what, f"returned {name} = {shorten(repr(value), 60)}: a number ≥ 0 was expected")


def _further_ratings(stage: object) -> list:
    """The stage's ratings beyond its first, as its kind's design facet gives them (a design's stage; a run's
    summary carries its planet–ring rating as ``planet_ring_rating``)."""
    if hasattr(stage, "planet_ring_rating"):
        ring = stage.planet_ring_rating
        return [] if ring is None else [ring]
    further = getattr(kinds.facet(kinds.kind_of(stage), "design"), "further_ratings", None)
    return list(further(stage)) if further is not None else []


def _missing(name: str) -> Callable:
    def absent(*args: Any) -> Any:
        raise AttributeError(f"the rated mesh has no {name}()")
    return absent
