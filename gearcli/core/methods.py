"""The one registry of integration methods: what each is and what it can do (no scipy import here).

Every other module (the design-file schema, the solver, ``method = "auto"``, the report's accuracy
study) reads this table; nothing else lists method names. ``stability_radius`` is the size of an
explicit method's stability region along the imaginary axis (the mesh modes are lightly damped),
``evals_per_step`` its right-hand-side evaluations per accepted step; ``sibling`` the method of the
same family that an accuracy check pairs with it; ``engines`` where it runs ("python": scipy; "compiled":
gearcli.engine, the ``fast`` extra).
"""

from __future__ import annotations

from gearcli.core.records import record


@record
class Method:
    """An integration method by name: whether it is implicit and takes a Jacobian."""

    name: str
    implicit: bool
    takes_jacobian: bool
    stability_radius: float  # explicit methods, along the imaginary axis; inf for implicit ones
    evals_per_step: int  # explicit methods; 0 for implicit ones (their cost follows Newton iterations)
    sibling: str
    engines: tuple[str, ...] = ("python",)
    summary: str = ""


_INF = float("inf")
_BOTH = ("python", "compiled")  # scipy's, and gearcli.engine's port of it
METHODS: dict[str, Method] = {m.name: m for m in (
    Method("RK45", False, False, 0.99, 6, "DOP853", _BOTH, summary="explicit Runge-Kutta 5(4), Dormand-Prince"),
    Method("DOP853", False, False, 5.95, 12, "RK45", _BOTH, summary="explicit Runge-Kutta 8(5,3), Dormand-Prince"),
    Method("Radau", True, True, _INF, 0, "BDF", _BOTH, summary="implicit Radau IIA order 5, L-stable"),
    Method("BDF", True, True, _INF, 0, "Radau", summary="implicit variable-order BDF"),
    Method("LSODA", True, True, _INF, 0, "BDF", summary="Adams/BDF switching (ODEPACK)"),
)}
AUTO = "auto"
NAMES: tuple[str, ...] = (AUTO, *METHODS)  # what a design file may give in [simulation] method
EXPLICIT: tuple[str, ...] = tuple(n for n, m in METHODS.items() if not m.implicit)
IMPLICIT: tuple[str, ...] = tuple(n for n, m in METHODS.items() if m.implicit)
EXPLICIT_METHOD = "DOP853"  # auto's explicit choice: the most stability per evaluation
IMPLICIT_METHOD = "Radau"  # auto's implicit choice


def method(name: str) -> Method:
    """The registry entry of ``name`` (KeyError for an unknown one)."""
    return METHODS[name]


def scipy_solver(name: str):
    """scipy's OdeSolver class of a method (imports scipy)."""
    import scipy.integrate  # lazy: scipy, start-up time of gearcli design

    return getattr(scipy.integrate, name)
