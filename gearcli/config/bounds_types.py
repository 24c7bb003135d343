"""The "0 or not nearly 0" bound of design-file numbers (docs/design-file.md, "0 or magnitude ≥ …"), and the
one base class of every design-file table (:class:`StrictTable`), which refuses a subnormal number in any
float key, list or table entry whatever the key's own bounds.

Quantities that may be 0 (a ramp, damping, backlash, a torque, a profile shift, an excitation amplitude) may
not be *nearly* 0: a nonzero magnitude below ``tiny`` (a subnormal like 1e-320 is the usual case: a unit
mistake or garbage) is refused with the bound named. Used by :mod:`gearcli.config.schema` and
:mod:`gearcli.config.excitation`.
"""


import inspect
import sys
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from contextvars import ContextVar
from typing import Any

from pydantic import BaseModel, ConfigDict, GetCoreSchemaHandler, GetJsonSchemaHandler, field_validator
from pydantic.json_schema import JsonSchemaValue
from pydantic_core import core_schema

from gearcli.core.records import record


@record
class NotTiny:
    """Annotation: 0 is allowed, but no magnitude in (0, tiny); in the JSON Schema a "not" range."""

    tiny: float

    def check(self, v: float) -> float:
        if v != 0 and abs(v) < self.tiny:
            raise ValueError(f"must be 0 or at least {self.tiny:g} in magnitude, got {v!r} (a value this small "
                             "is a mistake)")
        return v

    def __get_pydantic_core_schema__(self, source: Any, handler: GetCoreSchemaHandler) -> Any:
        return core_schema.no_info_after_validator_function(self.check, handler(source))

    def __get_pydantic_json_schema__(self, schema: Any, handler: GetJsonSchemaHandler) -> JsonSchemaValue:
        out = handler(schema)
        ranges = [{"exclusiveMinimum": 0, "exclusiveMaximum": self.tiny},
                  {"exclusiveMinimum": -self.tiny, "exclusiveMaximum": 0}]
        out["not"] = {"anyOf": ranges if out.get("minimum", 0) < 0 else ranges[:1]}
        return out


#: the optional tables a validator being built holds (None: all), :func:`given_tables`
_GIVEN: ContextVar[frozenset[str] | None] = ContextVar("gearcli_given_tables", default=None)


@contextmanager
def given_tables(given: frozenset[str] | None) -> Iterator[None]:
    """Within: a validator built of the design file holds the optional tables (:class:`IfGiven`) of ``given`` only
    (None: all; :func:`gearcli.config.schema.validate_design`); the classes' own validators hold every table."""
    token = _GIVEN.set(given)
    try:
        yield
    finally:
        _GIVEN.reset(token)


@record
class IfGiven:
    """Annotation of an optional table at ``path`` ("bearing", "input.motor", "stage.mesh": any stage's): its
    schema, except in a validator built for files that do not give it (:func:`given_tables`), where nothing ever
    reaches it (an absent key takes its default, unvalidated) and its schema is not built."""

    path: str

    def __get_pydantic_core_schema__(self, source: Any, handler: GetCoreSchemaHandler) -> Any:
        given = _GIVEN.get()
        if given is not None and self.path not in given:
            return core_schema.any_schema()
        return handler(source)


#: every table of the design file: unknown keys, NaN, infinity and type coercion refused. ``defer_build``: a
#: table's validator is built when it is first used (the design file's, once, with every table in it), not when
#: its class is created: ~35 validators compiled at import were each compiled again inside the file's
STRICT = ConfigDict(extra="forbid", strict=True, allow_inf_nan=False, frozen=True, defer_build=True)
SMALLEST_NORMAL = sys.float_info.min  # 2.2e-308: below it a float is subnormal (a mistake or garbage)


def _subnormal_in(value: Any, where: str = "") -> tuple[float, str] | None:
    """The first subnormal float in ``value`` (a number, or nested lists and dicts of them; tables are
    checked by their own model) and where it sits (``[1][0]``), or None."""
    if isinstance(value, float):
        return (value, where) if value != 0.0 and abs(value) < SMALLEST_NORMAL else None
    items = value.items() if isinstance(value, dict) else enumerate(value) if isinstance(value, (list, tuple)) else ()
    for k, v in items:
        found = _subnormal_in(v, f"{where}[{k!r}]" if isinstance(k, str) else f"{where}[{k}]")
        if found is not None:
            return found
    return None


def refuse_subnormal(value: Any) -> Any:
    """The design file's one rule for every float key: a subnormal value (5e-324, 1e-320) is refused."""
    found = _subnormal_in(value)
    if found is not None:
        v, where = found
        raise ValueError(f"must be 0 or at least {SMALLEST_NORMAL:g} in magnitude, got {v!r}"
                         + (f" (entry {where})" if where else "") + " (a subnormal number is a mistake)")
    return value


def _signature_once(fn: Callable) -> Callable:
    """``fn`` with its signature computed now (``__signature__``, what :func:`inspect.signature` would compute):
    pydantic reads a field validator's signature for every field it applies to (whether it takes an ``info``
    argument), and :class:`StrictTable`'s applies to every field of every table, ~210 in the design file's
    validator (~2 ms of its ~18 ms build)."""
    fn.__signature__ = inspect.signature(fn)  # type: ignore[attr-defined]
    return fn


class StrictTable(BaseModel):
    """Base of every design-file table: :data:`STRICT`, and :func:`refuse_subnormal` on every field (the rule
    lives here once, so a key added later is covered without a word)."""

    model_config = STRICT

    @field_validator("*", mode="after")
    @classmethod
    @_signature_once
    def _no_subnormal(cls, value: Any) -> Any:
        # called on every field of every table (~64 a seed file): a plain float, or a value that holds none (a
        # whole number, a text, a flag, None, a table checked by its own model), is answered here as
        # refuse_subnormal answers it, without its search
        kind = type(value)
        if kind is float:
            return value if value == 0.0 or not abs(value) < SMALLEST_NORMAL else refuse_subnormal(value)
        return value if kind in _NO_FLOATS or isinstance(value, BaseModel) else refuse_subnormal(value)


#: the types of a design-file value that holds no float (refuse_subnormal returns it as it is)
_NO_FLOATS = frozenset({int, bool, str, type(None)})
