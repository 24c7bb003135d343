"""Element types of the torsional model: one protocol, one registry (the element API).

An element joins two or more bodies, given by index, each through a lever (a radius; 1 for a torsional
element). Its deflection is ``delta = sum_j s_j r_j theta_j`` with the signs ``SIGNS`` it declares (two
bodies: ``(+1, -1)``, so ``delta = r_a theta_a - r_b theta_b``), and its force ``F`` puts ``-s_j r_j F`` on
body j. The assembly (:mod:`gearcli.model.assembly`) is the only place that knows indices; the right-hand
side, the Jacobian, the outputs, the linearisation and the compiled kernel scatter each element's force to
its bodies by index and ask the element everything else through this protocol. Nothing outside an element
module switches on its kind: the registry (:func:`register`, :func:`law_of`) replaces every kind switch.

An element module (:class:`ElementLaw`) defines ``NAME``, ``SIGNS``, ``PARAMS`` (the names of its
parameter row), ``CHANNELS`` (its output channels besides force, deflection and stored energy) and

    force(P, d, dd, phi, wphi) -> (F, dF_dd, dF_ddd, dF_dphi, dF_dwphi, p_damp, p_elastic_tv, p_te)

in plain ``math`` on floats (so numba can compile it unchanged): ``P`` the parameter row (a tuple or an
array), ``d``/``dd`` the deflection and its rate, ``phi`` the phase in cycles of the element's first body,
``phase_per_rad(P) theta_a`` (a mesh: ``z_p theta_p / 2 pi``), and ``wphi`` its rate (both 0 unless the
element is ``phased``/``excited``; cycles rather than radians so that the phase is formed exactly as
before the element redesign: a rattling mesh is sensitive to its last bit), ``p_damp`` the power the
element dissipates, ``p_elastic_tv`` the power into a time-varying spring, ``p_te`` the power a prescribed
motion (a transmission error) does on the bodies (``-F de/dt``; part of the input work).
``power_gradient(P, d, dd, phi, wphi)`` gives the partials of the three powers by (d, dd, phi, wphi) (the
Jacobian's energy rows), ``potential(P, d, phi)`` the stored elastic energy, ``channel(P, i, d, phi)`` the
value of output channel ``CHANNELS[i]``, ``static_deflection(P, F)`` the deflection that carries ``F`` in
steady state, ``deflection_scale(P, F, floor)`` the deflection's scale (absolute tolerances),
``tangent(P, F, stiffest_phase)`` the (stiffness, damping, static deflection) of the law linearised at
``|F|``, ``linear_row(P, factor)`` the row of the law frozen linear (energy scale), ``assembled(P, F,
m_e)`` the row once the assembly knows the static force and the equivalent mass of the bodies it joins,
``phase_per_rad(P)``, ``cycle_period_s(P, w)`` (the period of its own cycle at the speed ``w`` of its
first body: a mesh's mesh period; 0 for none), ``makes_excitation(P)`` (it excites the scene once per such
cycle: time-varying stiffness, transmission error, stiffness harmonics), ``self_exciting(P)`` (the law
makes its own harmonics: Hertzian, time-varying, backlash) and the flags ``damped``, ``time_varying``,
``phased``, ``excited``.

An element that loses power in the direction the power flows (a gear mesh's efficiency) provides the loss
hook :data:`LOSS_HOOK` besides: ``lossy(P)`` (this row loses), ``efficiency(P)``, ``loss_sides(P)`` (which
body slots make the two pitch-line speeds and take the two side forces, with their shares),
``loss_factors(P, f, va, vb)`` (the two side forces and their partials), ``with_loss_width(P, W)`` (the
row with the power scale ``W`` of the power-flow sign) and ``LOSS_WIDTH`` (that scale over the static force
times the nominal pitch-line speed). The assembly, the generated Python and the outputs call
it by name (:func:`loses`); no element without it loses power.

An element may also provide the vectorised hook :data:`SERIES_HOOK`, ``series(P, d, dd, phi, wphi)``: the force,
the stored energy and the channels at many samples at once (numpy arrays), value for value what ``force``,
``potential`` and ``channel`` give sample by sample, or None for a row it does not cover. The outputs of a
run on the Python engine use it where it answers (:func:`series_of`); without it they call the scalar laws.
And the hook :data:`RHS_HOOK`, ``rhs_force(P, d, dd)``: the force and the damping power of a row that is not
``phased``, value for value ``force``'s first and sixth numbers; the generated Python right-hand side, which reads
no other number of such a row, calls it there instead of ``force`` (~40 % less time a call for the mesh).

Torques on the end bodies (input torque ripple, load fluctuation) are laws of :mod:`.torque`.
"""

from __future__ import annotations

import types as _types
from types import ModuleType
from typing import Protocol

from gearcli.core.records import record

N_HARM = 8  # transmission-error / stiffness harmonics per mesh
N_PARAM = 27 + 4 * N_HARM  # width of every parameter row (the mesh's: gearcli.model.elements.mesh.PARAMS)
MAX_BODIES = 3  # bodies one element may join (a planet's mesh: sun or ring, planet, carrier)


class ElementLaw(Protocol):
    """What an element module provides (module text)."""

    NAME: str
    SIGNS: tuple[float, ...]
    PARAMS: tuple[str, ...]
    CHANNELS: tuple[str, ...]

    def pack(self, spec: object) -> object: ...
    def force(self, P, d, dd, phi, wphi) -> tuple: ...
    def power_gradient(self, P, d, dd, phi, wphi) -> tuple: ...
    def potential(self, P, d, phi) -> float: ...
    def channel(self, P, i, d, phi) -> float: ...
    def static_deflection(self, P, F) -> float: ...
    def deflection_scale(self, P, F, floor) -> float: ...
    def tangent(self, P, F, stiffest_phase) -> tuple[float, float, float]: ...
    def linear_row(self, P, factor) -> object: ...
    def assembled(self, P, F, m_e) -> object: ...
    def phase_per_rad(self, P) -> float: ...
    def cycle_period_s(self, P, w) -> float: ...
    def makes_excitation(self, P) -> bool: ...
    def self_exciting(self, P) -> bool: ...
    def damped(self, P) -> bool: ...
    def time_varying(self, P) -> bool: ...
    def phased(self, P) -> bool: ...
    def excited(self, P) -> bool: ...


@record
class ElementType:
    """A registered element type: its kind (the index the arrays carry), name and law module.
    ``compiled``: the compiled kernel (:mod:`gearcli.engine`) dispatches to it (its module is compiled and
    part of the kernel's cache key); an element registered without it runs on the Python engine."""

    kind: int
    name: str
    law: ModuleType
    compiled: bool = False

    @property
    def n_bodies(self) -> int:
        return len(self.law.SIGNS)


_REGISTRY: dict[int, ElementType] = {}


#: what an element module must define (:class:`ElementLaw`)
PROTOCOL = ("NAME", "SIGNS", "PARAMS", "CHANNELS", "pack", "force", "power_gradient", "potential", "channel",
            "static_deflection", "deflection_scale", "tangent", "linear_row", "assembled", "phase_per_rad",
            "cycle_period_s", "makes_excitation", "self_exciting", "damped", "time_varying", "phased", "excited")


#: the optional loss hook (module text): an element provides all of it or none
LOSS_HOOK = ("lossy", "efficiency", "loss_sides", "loss_factors", "with_loss_width", "LOSS_WIDTH")

#: the optional vectorised hook (module text): ``series(P, d, dd, phi, wphi)``
SERIES_HOOK = "series"


#: the optional hook of the generated Python right-hand side (module text): ``rhs_force(P, d, dd)``
RHS_HOOK = "rhs_force"


def series_of(law: ModuleType, P, d, dd, phi, wphi) -> tuple | None:
    """``(F, stored energy, channels)`` at every sample from the element's vectorised hook, or None where it has
    none or its row is outside what the hook covers (the caller then evaluates the scalar laws sample by
    sample)."""
    hook = getattr(law, SERIES_HOOK, None)
    return None if hook is None else hook(P, d, dd, phi, wphi)


def loses(law: ModuleType, P) -> bool:
    """The element loses power with the row ``P`` (its loss hook says so; an element without the hook never)."""
    lossy = getattr(law, "lossy", None)
    return lossy is not None and bool(lossy(P))


def register(law: ModuleType, *, compiled: bool = False) -> ElementType:
    """Register an element module; its kind is the next free index (idempotent for the same module).
    ``compiled``: also compile it into the kernel (a new cache, compiled once)."""
    missing = [name for name in PROTOCOL if not hasattr(law, name)]
    if missing:
        raise TypeError(f"{law.__name__} is not an element module: it lacks {', '.join(missing)}")
    partial = [name for name in LOSS_HOOK if not hasattr(law, name)]
    if 0 < len(partial) < len(LOSS_HOOK):
        raise TypeError(f"{law.__name__} has part of the loss hook: it lacks {', '.join(partial)}")
    for et in _REGISTRY.values():
        if et.law is law:
            return et
        if et.name == law.NAME:
            raise ValueError(f"an element named {law.NAME!r} is registered already")
    if not 2 <= len(law.SIGNS) <= MAX_BODIES:
        raise ValueError(f"an element joins 2 to {MAX_BODIES} bodies, {law.NAME!r} declares {len(law.SIGNS)}")
    if len(law.PARAMS) > N_PARAM:
        raise ValueError(f"at most {N_PARAM} parameters per element, {law.NAME!r} has {len(law.PARAMS)}")
    et = ElementType(len(_REGISTRY), law.NAME, law, compiled)
    _REGISTRY[et.kind] = et
    return et


def law_of(kind: int) -> ModuleType:
    """The law module of a kind."""
    return _REGISTRY[int(kind)].law


def kind_of(name: str) -> int:
    """The kind of a registered element name."""
    for et in _REGISTRY.values():
        if et.name == name:
            return et.kind
    raise KeyError(name)


def registered() -> tuple[ElementType, ...]:
    """Every registered element type, in kind order."""
    return tuple(_REGISTRY[k] for k in sorted(_REGISTRY))


def adopt(module: ModuleType, scope: dict) -> None:
    """Another module's functions and constants as the calling module's own (``adopt(plain, globals())``):
    each function re-created on the caller's globals, so the compiled engine, which compiles a module's own
    functions, compiles them there. Its ``NAME`` and ``SIGNS`` are not taken; a constant the caller has
    already is kept, a function the caller defines after the call replaces the adopted one."""
    for name, obj in vars(module).items():
        if name.startswith("__") or name in ("NAME", "SIGNS"):
            continue
        if isinstance(obj, _types.FunctionType) and obj.__module__ == module.__name__:
            fn = _types.FunctionType(obj.__code__, scope, name, obj.__defaults__, obj.__closure__)
            fn.__qualname__, fn.__doc__ = obj.__qualname__, obj.__doc__
            scope[name] = fn
        elif name not in scope:
            scope[name] = obj


def compiled_types() -> tuple[ElementType, ...]:
    """The element types the compiled kernel dispatches to, in kind order."""
    return tuple(et for et in registered() if et.compiled)


from gearcli.model.elements import mesh, planet_mesh, spring  # noqa: E402 - the built-in laws read N_PARAM above
from gearcli.model.elements import plain as plain  # noqa: E402 - the protocol's defaults, for element modules (adopt)

KIND_SPRING = register(spring, compiled=True).kind  # torsional spring-damper: couplings, flexible shafts
KIND_MESH = register(mesh, compiled=True).kind  # gear mesh along its transverse line of action (Adams IMPACT)
KIND_PLANET_MESH = register(planet_mesh, compiled=True).kind  # a planet's mesh joining planet, sun or ring, and carrier
