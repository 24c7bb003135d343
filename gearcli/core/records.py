"""``@record``: a frozen dataclass whose methods but ``__init__`` are made without compiling source.

Python 3.11's ``dataclasses`` writes each generated method as source text and compiles it (``exec``): six per
frozen class (``__init__``, ``__repr__``, ``__eq__``, ``__hash__``, ``__setattr__``, ``__delattr__``), ~0.13 ms
each on the reference machine. gearcli creates ~80 such classes before a one-shot ``simulate`` has read its
file. :func:`record` compiles only ``__init__``: ``__eq__``, ``__hash__`` and ``__repr__`` are closures over the
class's field names (``operator.attrgetter`` builds the same tuples the generated methods compare and hash, in
C), and so are ``__setattr__`` and ``__delattr__``, which refuse what ``dataclass(frozen=True)``'s refuse once
the instance is made. The class is made by ``dataclass(frozen=False)``, whose ``__init__`` assigns each field
once through that ``__setattr__``: a field's first assignment, in the constructor, is the one it lets through
(a field ``init=False`` is set by ``__post_init__`` with ``object.__setattr__``, as a frozen dataclass's).

What the class does is ``dataclass(frozen=True)``'s: the same fields, ``__init__``, ``replace``, equality (same
class and equal compared fields), hash (of the hashed fields' tuple), repr (the fields with ``repr=True``,
``...`` on recursion), and after construction no field assigned or deleted and, on the class's own instances, no
attribute added (``FrozenInstanceError``); a method the class body defines is kept
(tests/unit/test_records.py checks each against ``dataclass(frozen=True)``). What differs: the dataclass
parameters say ``frozen=False`` (so ``dataclass(frozen=True)`` cannot subclass a record; ``@record`` can), and
constructing an instance costs ~0.1 us a field more (the Python ``__setattr__``).
"""

from __future__ import annotations

import dataclasses
import reprlib
from collections.abc import Callable
from operator import attrgetter
from typing import Any, TypeVar, cast, dataclass_transform

T = TypeVar("T")


def fields_getter(names: tuple[str, ...]) -> Callable[[Any], tuple]:
    """obj -> the tuple of its attributes ``names``, in C (``attrgetter`` returns a bare value for one name, so one
    name is wrapped, and no names give ``()``): what a record compares, hashes and shows, and what
    :func:`gearcli.design.compute` checks for finiteness."""
    if len(names) == 1:
        one = attrgetter(names[0])
        return lambda obj: (one(obj),)
    if not names:
        return lambda obj: ()
    return attrgetter(*names)


def _methods(cls: type, fields: tuple[dataclasses.Field, ...]) -> dict[str, Callable]:
    compared = fields_getter(tuple(f.name for f in fields if f.compare))
    hashed = fields_getter(tuple(f.name for f in fields if (f.compare if f.hash is None else f.hash)))
    shown = tuple(f.name for f in fields if f.repr)
    shown_values = fields_getter(shown)

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

    names = frozenset(f.name for f in fields)
    owner: Any = cls  # super(owner, self): the next __setattr__ after this class's, as dataclass's
    # the next __setattr__ of the class's own instances (object's for a record without bases): their constructor's
    # assignments go through it directly (a super() call per field cost as much again)
    parent = next(k.__dict__["__setattr__"] for k in cls.__mro__[1:] if "__setattr__" in k.__dict__)

    def __setattr__(self, name, value):  # noqa: N807 - dataclass's frozen rule, after the constructor's assignments
        if type(self) is owner:
            if name in names and name not in self.__dict__:  # the constructor's one assignment of the field
                return parent(self, name, value)
        elif name not in names or name not in self.__dict__:  # a subclass's instance: only the fields are frozen
            return super(owner, self).__setattr__(name, value)
        raise dataclasses.FrozenInstanceError(f"cannot assign to field {name!r}")

    def __delattr__(self, name):  # noqa: N807
        if type(self) is owner or name in names:
            raise dataclasses.FrozenInstanceError(f"cannot delete field {name!r}")
        super(owner, self).__delattr__(name)

    out: dict[str, Callable[..., Any]] = {"__eq__": __eq__, "__hash__": __hash__, "__repr__": __repr__,
                                          "__setattr__": __setattr__, "__delattr__": __delattr__}
    for fn in out.values():
        fn.__qualname__ = f"{cls.__qualname__}.{fn.__name__}"
    return out


@dataclass_transform(frozen_default=True, field_specifiers=(dataclasses.field, dataclasses.Field))
def record(cls: type[T]) -> type[T]:
    """``@dataclass(frozen=True)`` with five methods made without ``exec`` (module docstring)."""
    body = cls.__dict__
    own_eq = "__eq__" in body
    own_repr = "__repr__" in body
    # dataclass's rule: a __hash__ the body sets is kept, unless it is the None Python puts there for an own __eq__
    own_hash = "__hash__" in body and not (body["__hash__"] is None and own_eq)
    for name in ("__setattr__", "__delattr__"):
        if name in body:  # as dataclass(frozen=True)
            raise TypeError(f"Cannot overwrite attribute {name} in class {cls.__name__}")
    cls = dataclasses.dataclass(eq=False, repr=False)(cls)  # frozen by the methods below (module docstring)
    methods = _methods(cls, dataclasses.fields(cast(Any, cls)))
    cls.__setattr__ = methods["__setattr__"]  # type: ignore[method-assign]
    cls.__delattr__ = methods["__delattr__"]  # type: ignore[method-assign]
    if not own_repr:
        cls.__repr__ = methods["__repr__"]  # type: ignore[method-assign]
    if not own_eq:
        cls.__eq__ = methods["__eq__"]  # type: ignore[method-assign]
    if not own_hash:
        cls.__hash__ = methods["__hash__"]  # type: ignore[method-assign]
    return cls
