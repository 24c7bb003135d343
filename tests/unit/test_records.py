"""``@record`` behaves as ``@dataclass(frozen=True)``: the same fields, constructor, frozenness, ``replace``,
equality, hash and repr, a method of the class body kept, and a subclass its own record."""

from __future__ import annotations

import copy
import dataclasses
import inspect
import pickle
from typing import Any

import pytest

from gearcli.core.records import record


@record
class Sample:
    """A record at module level (pickle finds its class by name)."""

    a: float
    b: tuple = ()


def _pair(body: dict, name: str = "Point"):
    """The same class made by ``@record`` and by ``@dataclass(frozen=True)``."""
    ann = {"x": "float", "y": "float", "tag": "str", "note": "str", "items": "tuple"}
    ns = {"__annotations__": ann, "__module__": __name__, "__doc__": "A point.",
          "tag": "a", "note": dataclasses.field(default="", compare=False, repr=False),
          "items": dataclasses.field(default=(), hash=False), **body}
    return record(type(name, (), dict(ns))), dataclasses.dataclass(frozen=True)(type(name, (), dict(ns)))


def test_equality_hash_and_repr_as_a_frozen_dataclass():
    ours, theirs = _pair({})
    for args in [(1.0, 2.0), (1.0, 2.0, "b", "x", (1, 2)), (float("nan"), 0.0)]:
        a, b = ours(*args), theirs(*args)
        assert repr(a) == repr(b)
        assert hash(a) == hash(b)
        assert (a == ours(*args)) == (b == theirs(*args))
    assert ours(1.0, 2.0, note="x") == ours(1.0, 2.0, note="y")  # note: compare=False
    assert ours(1.0, 2.0) != ours(1.0, 3.0)
    assert ours(1.0, 2.0, items=(1,)) != ours(1.0, 2.0, items=(2,))  # compared, not hashed
    assert hash(ours(1.0, 2.0, items=(1,))) == hash(ours(1.0, 2.0, items=(2,)))
    assert ours(1.0, 2.0) != theirs(1.0, 2.0)  # another class: NotImplemented both ways
    assert ours(1.0, 2.0).__eq__(object()) is NotImplemented
    assert [f.name for f in dataclasses.fields(ours)] == [f.name for f in dataclasses.fields(theirs)]
    assert ours.__match_args__ == theirs.__match_args__ and ours.__doc__ == theirs.__doc__


def test_frozen_replace_pickle_and_recursion():
    ours, _ = _pair({})
    a = ours(1.0, 2.0)
    with pytest.raises(dataclasses.FrozenInstanceError):
        a.x = 3.0  # type: ignore[misc]
    with pytest.raises(dataclasses.FrozenInstanceError):
        del a.x  # type: ignore[misc]
    assert dataclasses.replace(a, y=5.0) == ours(1.0, 5.0)
    assert pickle.loads(pickle.dumps(Sample(1.5, (2,)))) == Sample(1.5, (2,))
    b = ours(1.0, 2.0, items=[])
    b.items.append(b)  # a record inside itself: "..." as dataclass's repr
    assert repr(b) == "Point(x=1.0, y=2.0, tag='a', items=[...])"


def test_the_class_bodys_methods_are_kept():
    def eq(self, other):
        return True

    ours, theirs = _pair({"__eq__": eq, "__repr__": lambda self: "mine", "__hash__": lambda self: 7})
    assert ours(1.0, 2.0) == ours(3.0, 4.0) and repr(ours(1.0, 2.0)) == "mine" and hash(ours(1.0, 2.0)) == 7
    ours, theirs = _pair({"__eq__": eq, "__hash__": None})  # an own __eq__ alone: the fields' hash, as dataclass
    assert hash(ours(1.0, 2.0)) == hash(theirs(1.0, 2.0))


def test_a_subclass_is_a_record_of_its_own():
    base, _ = _pair({})
    sub = record(type("Sub", (base,), {"__annotations__": {"z": "int"}, "__module__": __name__, "z": 0,
                                       "__doc__": "A sub."}))
    s = sub(1.0, 2.0, z=3)
    assert repr(s) == "Sub(x=1.0, y=2.0, tag='a', items=(), z=3)"
    assert s != base(1.0, 2.0) and s == sub(1.0, 2.0, z=3) and hash(s) == hash(sub(1.0, 2.0, z=3))
    with pytest.raises(dataclasses.FrozenInstanceError):
        s.z = 4  # type: ignore[misc]


def _refuses(obj, action) -> bool:
    try:
        action(obj)
    except dataclasses.FrozenInstanceError:
        return True
    return False


def test_frozen_as_a_frozen_dataclass_after_the_constructor():
    # the class is made by dataclass(frozen=False) and frozen by its own __setattr__ and __delattr__: each refusal
    # of dataclass(frozen=True)'s, on the class's instances and on a plain subclass's (which may add attributes)
    ours, theirs = _pair({})
    plain = [type("Plain", (cls,), {}) for cls in (ours, theirs)]
    actions = [lambda o: setattr(o, "x", 9.0), lambda o: setattr(o, "note", "n"), lambda o: setattr(o, "extra", 1),
               lambda o: delattr(o, "y"), lambda o: delattr(o, "extra")]
    for a, b in [(ours(1.0, 2.0), theirs(1.0, 2.0)), (plain[0](1.0, 2.0), plain[1](1.0, 2.0))]:
        assert [_refuses(a, act) for act in actions] == [_refuses(b, act) for act in actions]
    sub = plain[0](1.0, 2.0)
    sub.extra = 1  # a plain subclass's own attribute, as dataclass allows
    assert sub.extra == 1 and sub.x == 1.0
    with pytest.raises(TypeError, match="Cannot overwrite attribute __setattr__"):
        record(type("Own", (), {"__annotations__": {"x": "float"}, "__module__": __name__,
                                "__setattr__": lambda self, name, value: None}))


def test_a_field_set_after_init_is_frozen_too():
    # a field init=False is set in __post_init__ (object.__setattr__, as a frozen dataclass needs) and then frozen
    def post_init(self):
        object.__setattr__(self, "total", self.x + self.y)

    ann = {"x": "float", "y": "float", "total": "float"}
    cls: Any = record(type("Sum", (), {"__annotations__": ann, "__module__": __name__, "__post_init__": post_init,
                                  "total": dataclasses.field(init=False), "__doc__": "A sum."}))
    s = cls(1.0, 2.0)
    assert s.total == 3.0 and repr(s) == "Sum(x=1.0, y=2.0, total=3.0)"
    with pytest.raises(dataclasses.FrozenInstanceError):
        s.total = 4.0
    assert copy.copy(s) == s and copy.deepcopy(s) == s and dataclasses.replace(s, x=2.0).total == 4.0


def _both(ns: dict, name: str = "Made"):
    """The same class body made by ``@record`` and by ``@dataclass(frozen=True)`` (each from its own copy)."""
    body = {"__module__": __name__, "__doc__": "Made.", **ns}
    return record(type(name, (), dict(body))), dataclasses.dataclass(frozen=True)(type(name, (), dict(body)))


def test_the_constructor_is_a_frozen_dataclasss():
    # defaults, a default factory (a fresh value each instance), keyword-only fields, fields init=False with a
    # default and with a factory, a field named self, and __post_init__ (called once, after every field is set)
    calls: list = []

    def post_init(self):
        calls.append(dict(vars(self)))

    ns = {"__annotations__": {"self": "int", "a": "float", "b": "list", "c": "str", "d": "int", "e": "list",
                              "k": "int"},
          "b": dataclasses.field(default_factory=list), "c": "x", "d": dataclasses.field(default=4, init=False),
          "e": dataclasses.field(default_factory=lambda: [1], init=False), "k": dataclasses.field(default=0, kw_only=True),
          "__post_init__": post_init}
    ours, theirs = _both(ns)
    assert str(inspect.signature(ours)) == str(inspect.signature(theirs))  # (each its own <factory> sentinel)
    assert ours.__init__.__annotations__ == theirs.__init__.__annotations__
    for args, kwargs in [((1, 2.0), {}), ((1, 2.0, [3], "y"), {"k": 5}), ((), {"self": 7, "a": 1.5, "c": "z"})]:
        a, b = ours(*args, **kwargs), theirs(*args, **kwargs)
        assert vars(a) == vars(b) and repr(a) == repr(b).replace(theirs.__qualname__, ours.__qualname__)
        assert calls[-1] == calls[-2] == vars(a)
    assert ours(1, 2.0).b is not ours(1, 2.0).b and ours(1, 2.0).e is not ours(1, 2.0).e
    for args in [(), (1,), (1, 2.0, [], "c", 9)]:  # too few, too many: the same refusals
        with pytest.raises(TypeError):
            ours(*args)
        with pytest.raises(TypeError):
            theirs(*args)
    with pytest.raises(TypeError, match="non-default argument 'b' follows default argument"):
        record(type("Bad", (), {"__annotations__": {"a": "int", "b": "int"}, "a": 1, "__module__": __name__}))



def test_the_constructor_made_without_compiling_its_source_is_dataclasss():
    # a record of plain fields (positional parameters without a default factory): its __init__ is made from a
    # template shared by the classes of its field count (defaults, __post_init__, a subclass adding fields), the
    # same parameters, annotations, assignments and refusals as dataclass's
    calls: list = []

    def post_init(self):
        calls.append(dict(vars(self)))

    ns = {"__annotations__": {"n": "int", "a": "float", "c": "str", "d": "tuple"}, "c": "x", "d": (),
          "__post_init__": post_init}
    ours, theirs = _both(ns)
    assert ours.__init__.__code__.co_qualname == "Made.__init__"  # not dataclass's __create_fn__.<locals>.__init__
    assert str(inspect.signature(ours)) == str(inspect.signature(theirs)) == \
        "(n: 'int', a: 'float', c: 'str' = 'x', d: 'tuple' = ()) -> None"
    assert ours.__init__.__annotations__ == theirs.__init__.__annotations__
    assert ours.__dataclass_params__.init and ours.__match_args__ == theirs.__match_args__
    for args, kwargs in [((1, 2.0), {}), ((1, 2.0, "y", (3,)), {}), ((), {"n": 7, "a": 1.5, "d": (4,)})]:
        a, b = ours(*args, **kwargs), theirs(*args, **kwargs)
        assert vars(a) == vars(b) and repr(a) == repr(b).replace(theirs.__qualname__, ours.__qualname__)
        assert calls[-1] == calls[-2] == vars(a)
    for args, kwargs in [((), {}), ((1,), {}), ((1, 2.0, "c", (), 9), {}), ((1, 2.0), {"e": 5}),
                         ((1, 2.0), {"n": 1})]:  # too few, too many, not a parameter, given twice
        with pytest.raises(TypeError) as mine:
            ours(*args, **kwargs)
        with pytest.raises(TypeError) as dataclasss:
            theirs(*args, **kwargs)
        assert str(mine.value).split("() ")[1] == str(dataclasss.value).split("() ")[1]
    sub = record(type("Sub", (ours,), {"__annotations__": {"z": "int"}, "__module__": __name__, "z": 0,
                                       "__doc__": "A sub."}))
    subd = dataclasses.dataclass(frozen=True)(type("Sub", (theirs,), {"__annotations__": {"z": "int"},
                                                                      "__module__": __name__, "z": 0}))
    assert sub.__init__.__code__.co_qualname == "Sub.__init__"
    assert str(inspect.signature(sub)) == str(inspect.signature(subd))
    assert vars(sub(1, 2.0, z=3)) == vars(subd(1, 2.0, z=3))
    with pytest.raises(TypeError, match="non-default argument 'b' follows default argument"):
        record(type("Bad", (), {"__annotations__": {"a": "int", "b": "int"}, "a": 1, "__module__": __name__,
                                "__doc__": "Bad."}))
