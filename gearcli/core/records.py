"""``@record``: a frozen dataclass whose methods are made without compiling source per class.

Python 3.11's ``dataclasses`` writes each generated method as source text and compiles it (``exec``): six per
frozen class (``__init__``, ``__repr__``, ``__eq__``, ``__hash__``, ``__setattr__``, ``__delattr__``), ~0.13 ms
each on the reference machine. gearcli creates ~80 such classes before a one-shot ``simulate`` has read its
file. :func:`record` compiles at most ``__init__`` (below): ``__eq__``, ``__hash__`` and ``__repr__`` are
closures over the class's field names (``operator.attrgetter`` builds the same tuples the generated methods
compare and hash, in C), and so are ``__setattr__`` and ``__delattr__``, which refuse what
``dataclass(frozen=True)``'s refuse once the instance is made. The class is made by ``dataclass(frozen=False)``,
whose ``__init__`` assigns each field once through that ``__setattr__``: a field's first assignment, in the
constructor, is the one it lets through (a field ``init=False`` is set by ``__post_init__`` with
``object.__setattr__``, as a frozen dataclass's).

What the class does is ``dataclass(frozen=True)``'s: the same fields, ``__init__``, ``replace``, equality (same
class and equal compared fields), hash (of the hashed fields' tuple), repr (the fields with ``repr=True``,
``...`` on recursion), and after construction no field assigned or deleted and, on the class's own instances, no
attribute added (``FrozenInstanceError``); a method the class body defines is kept
(tests/unit/test_records.py checks each against ``dataclass(frozen=True)``). What differs: the dataclass
parameters say ``frozen=False`` (so ``dataclass(frozen=True)`` cannot subclass a record; ``@record`` can), and
constructing an instance whose ``__init__`` is dataclass's own costs ~0.5 us a field more (the Python
``__setattr__``); the plain ``__init__`` below sets its fields as a frozen dataclass's does.

Nor is ``__init__`` (:func:`_plain_init`) where every field is plain (a positional ``__init__`` parameter without a
default factory; no ``InitVar`` or ``ClassVar``) and the class has a docstring: Python 3.11's ``dataclasses``
writes it as source and compiles it, one ``compile`` a class (~100 us for eight fields), where one code object
compiled per field count and ``__post_init__`` (:func:`_init_template`), the field names put in
(``CodeType.replace``), makes the same function for every class of that shape (~3 us a class once compiled): the
same parameters, defaults and annotations, one ``object.__setattr__(self, "name", name)`` per field in field
order (as ``dataclass(frozen=True)``'s, not through the class's ``__setattr__``), then
``self.__post_init__()`` if the class has one (74 classes, 28 shapes on a one-shot ``simulate``). Any other
record's ``__init__`` is dataclass's own.
"""

from __future__ import annotations

import dataclasses
import reprlib
import sys
from collections.abc import Callable
from functools import cache
from operator import attrgetter
from types import CellType, CodeType, FunctionType
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


#: annotations that make a class attribute something other than a plain field (dataclass's pseudo-fields)
_PSEUDO = ("ClassVar", "InitVar", "KW_ONLY")


def _plain_field(f: dataclasses.Field) -> bool:
    """A field that is a positional ``__init__`` parameter without a default factory."""
    return f.init and f.default_factory is dataclasses.MISSING and f.kw_only in (dataclasses.MISSING, False)


def _plain(cls: type) -> bool:
    """Whether dataclass's ``__init__`` of ``cls`` would be the plain one :func:`_plain_init` makes: a docstring
    (dataclass otherwise formats the constructor's signature into ``__doc__``), no ``__init__`` of the body's own,
    no pseudo-field, and every field, its own and its dataclass bases', plain (:func:`_plain_field`)."""
    body = cls.__dict__
    annotations = body.get("__annotations__", {})
    if not cls.__doc__ or "__init__" in body or "self" in annotations:
        return False
    if any(word in str(a) for a in annotations.values() for word in _PSEUDO):
        return False
    if any(isinstance(v, dataclasses.Field) and not _plain_field(v) for k, v in body.items() if k in annotations):
        return False
    for base in cls.__mro__[1:]:
        fields = base.__dict__.get("__dataclass_fields__")
        if fields is not None:
            given = dataclasses.fields(base)
            if len(given) != len(fields) or "self" in fields or not all(_plain_field(f) for f in given):
                return False
    return True


@cache
def _init_template(n: int, post_init: bool) -> CodeType:
    """The code of ``__init__(self, _0, ..., _{n-1})`` setting attribute ``"_i"`` to ``_i`` in order with
    ``object.__setattr__`` (the closure's ``_set``, as a frozen dataclass's constructor does), then calling
    ``self.__post_init__()`` if asked: compiled once per shape, the names put in by :func:`_plain_init`."""
    params = "".join(f", _{i}" for i in range(n))
    lines = [f"        _set(self, '_{i}', _{i})" for i in range(n)]
    lines += ["        self.__post_init__()"] if post_init else []
    source = "\n".join(["def make(_set):", f"    def __init__(self{params}):", *(lines or ["        pass"]),
                        "    return __init__"]) + "\n"
    namespace: dict[str, Any] = {}
    exec(compile(source, "<string>", "exec"), {}, namespace)  # noqa: S102 - our own template
    return namespace["make"](object.__setattr__).__code__


#: the template's closure: the one cell holding ``object.__setattr__``
_SET = (CellType(object.__setattr__),)


def _plain_init(cls: type, fields: tuple[dataclasses.Field, ...]) -> Callable[..., None]:
    """dataclass's ``__init__`` of a class with plain fields (:func:`_plain`): the same parameters, defaults,
    annotations, qualified name, globals and assignments, from :func:`_init_template` (module docstring)."""
    seen_default = False
    for f in fields:  # dataclass's own check, with its message
        if f.default is not dataclasses.MISSING:
            seen_default = True
        elif seen_default:
            raise TypeError(f"non-default argument {f.name!r} follows default argument")
    code = _init_template(len(fields), hasattr(cls, "__post_init__"))
    names = {f"_{i}": f.name for i, f in enumerate(fields)}
    qualname = f"{cls.__qualname__}.__init__"
    code = code.replace(co_varnames=tuple(names.get(v, v) for v in code.co_varnames),
                        co_consts=tuple(names.get(c, c) if isinstance(c, str) else c for c in code.co_consts),
                        co_qualname=qualname)
    module = sys.modules.get(cls.__module__)
    defaults = tuple(f.default for f in fields if f.default is not dataclasses.MISSING)
    init = FunctionType(code, module.__dict__ if module is not None else {}, "__init__", defaults or None, _SET)
    init.__qualname__ = qualname
    init.__annotations__ = {**{f.name: f.type for f in fields}, "return": None}
    return init


@dataclass_transform(frozen_default=True, field_specifiers=(dataclasses.field, dataclasses.Field))
def record(cls: type[T]) -> type[T]:
    """``@dataclass(frozen=True)`` with five methods made without ``exec``, and ``__init__`` too where the fields
    are plain (module docstring)."""
    body = cls.__dict__
    own_eq = "__eq__" in body
    own_repr = "__repr__" in body
    # dataclass's rule: a __hash__ the body sets is kept, unless it is the None Python puts there for an own __eq__
    own_hash = "__hash__" in body and not (body["__hash__"] is None and own_eq)
    for name in ("__setattr__", "__delattr__"):
        if name in body:  # as dataclass(frozen=True)
            raise TypeError(f"Cannot overwrite attribute {name} in class {cls.__name__}")
    plain = _plain(cls)
    # frozen by the methods below (module docstring)
    cls = dataclasses.dataclass(eq=False, repr=False, init=not plain)(cls)
    fields = dataclasses.fields(cast(Any, cls))
    if plain:
        cls.__init__ = _plain_init(cls, fields)  # type: ignore[method-assign]
        cast(Any, cls).__dataclass_params__.init = True  # as dataclass(frozen=True)'s parameters say
    methods = _methods(cls, fields)
    cls.__setattr__ = methods["__setattr__"]  # type: ignore[method-assign]
    cls.__delattr__ = methods["__delattr__"]  # type: ignore[method-assign]
    if not own_repr:
        cls.__repr__ = methods["__repr__"]  # type: ignore[method-assign]
    if not own_eq:
        cls.__eq__ = methods["__eq__"]  # type: ignore[method-assign]
    if not own_hash:
        cls.__hash__ = methods["__hash__"]  # type: ignore[method-assign]
    return cls
