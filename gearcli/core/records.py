"""``@record``: a frozen dataclass whose comparison, hash and repr are made without compiling source.

Python 3.11's ``dataclasses`` writes each generated method as source text and compiles it (``exec``): six per
frozen class (``__init__``, ``__repr__``, ``__eq__``, ``__hash__``, ``__setattr__``, ``__delattr__``). gearcli
creates ~80 such classes before a one-shot ``simulate`` has read its file, and compiling their ~500 methods is
~10 % of the command's work. :func:`record` is ``dataclass(frozen=True)`` with ``__eq__``, ``__hash__`` and
``__repr__`` taken from closures over the class's field names instead (``operator.attrgetter`` builds the same
tuples the generated methods compare and hash, in C), so each class compiles three methods, not six. What the
class does is ``dataclass(frozen=True)``'s: the same fields, ``__init__``, frozenness, ``replace``, equality
(same class and equal compared fields), hash (of the hashed fields' tuple) and repr (the fields with
``repr=True``, ``...`` on recursion), and a method the class body defines is kept
(tests/unit/test_records.py checks each against ``dataclass(frozen=True)``).
"""

from __future__ import annotations

import dataclasses
import reprlib
from collections.abc import Callable
from operator import attrgetter
from typing import Any, TypeVar, cast, dataclass_transform

T = TypeVar("T")


def _getter(names: tuple[str, ...]) -> Callable[[Any], tuple]:
    """obj -> the tuple of its attributes ``names`` (``attrgetter`` returns a bare value for one name)."""
    if len(names) == 1:
        one = attrgetter(names[0])
        return lambda obj: (one(obj),)
    if not names:
        return lambda obj: ()
    return attrgetter(*names)


def _methods(cls: type, fields: tuple[dataclasses.Field, ...]) -> dict[str, Callable]:
    compared = _getter(tuple(f.name for f in fields if f.compare))
    hashed = _getter(tuple(f.name for f in fields if (f.compare if f.hash is None else f.hash)))
    shown = tuple(f.name for f in fields if f.repr)
    shown_values = _getter(shown)

    def __eq__(self, other):  # noqa: N807 - dataclass's: same class, equal compared fields
        if other.__class__ is self.__class__:
            return compared(self) == compared(other)
        return NotImplemented

    def __hash__(self):  # noqa: N807
        return hash(hashed(self))

    @reprlib.recursive_repr()
    def __repr__(self):  # noqa: N807
        values = shown_values(self)
        return (self.__class__.__qualname__ + "("
                + ", ".join(f"{name}={value!r}" for name, value in zip(shown, values, strict=True)) + ")")

    out: dict[str, Callable[..., Any]] = {"__eq__": __eq__, "__hash__": __hash__, "__repr__": __repr__}
    for fn in out.values():
        fn.__qualname__ = f"{cls.__qualname__}.{fn.__name__}"
    return out


@dataclass_transform(frozen_default=True, field_specifiers=(dataclasses.field, dataclasses.Field))
def record(cls: type[T]) -> type[T]:
    """``@dataclass(frozen=True)`` with three methods made without ``exec`` (module docstring)."""
    body = cls.__dict__
    own_eq = "__eq__" in body
    own_repr = "__repr__" in body
    # dataclass's rule: a __hash__ the body sets is kept, unless it is the None Python puts there for an own __eq__
    own_hash = "__hash__" in body and not (body["__hash__"] is None and own_eq)
    cls = dataclasses.dataclass(frozen=True, eq=False, repr=False)(cls)
    methods = _methods(cls, dataclasses.fields(cast(Any, cls)))
    if not own_repr:
        cls.__repr__ = methods["__repr__"]  # type: ignore[method-assign]
    if not own_eq:
        cls.__eq__ = methods["__eq__"]  # type: ignore[method-assign]
    if not own_hash:
        cls.__hash__ = methods["__hash__"]  # type: ignore[method-assign]
    return cls
