"""The element protocol's defaults for a plain torsional element: its law is linear (its own linear row), it
needs nothing from the bodies, has no phase and no cycle of its own, excites nothing and has no time-varying
stiffness. An element module takes them with ``adopt(plain, globals())`` (:func:`gearcli.model.elements.adopt`:
each function re-created as the module's own, so the compiled engine compiles it there) and defines what
differs after that line (the spring, a damper).
"""

from __future__ import annotations


def linear_row(P, factor):
    """The law is linear already: its own row."""
    return P


def assembled(P, F, m_e):
    """Nothing to fill in from the bodies."""
    return P


def phase_per_rad(P):
    return 0.0


def cycle_period_s(P, w):
    return 0.0


def makes_excitation(P) -> bool:
    return False


def self_exciting(P) -> bool:
    return False


def time_varying(P) -> bool:
    return False


def phased(P) -> bool:
    return False


def excited(P) -> bool:
    return False
