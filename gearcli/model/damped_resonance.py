"""Resonances of a damped mode that no undamped mode stands for (:func:`gearcli.model.modes.resonances`).

The modes are the undamped chain's, each with the damping of the damped eigenvalue whose shape matches it
(:func:`gearcli.model.damping.modal_damping`). Strong damping at one body changes the chain: a motor's slip damping
(167 N m s/rad on a 0.5 kg m^2 rotor) holds the rotor at the frequencies of the train, so the free chain rings at
5.34 Hz (zeta 0.174), the drum swinging against a train whose motor stands nearly still (the held input's 5.41 Hz
mode), while its undamped modes are 0 (rigid), 20.2, 83.4 and 1037 Hz: that eigenvalue's shape is the rigid-body
rotation's more than any elastic mode's, so no mode takes it, and a load fluctuation at 5.34 Hz, which drives the
drum's inertia torque to 2.9 times its amplitude, was warned about by nothing.

Each oscillating eigenvalue that no mode takes (its Im lambda none of the modes' ``damped_frequency_Hz``) is checked as
a mode of its own, at the frequency it rings at, f_d = Im lambda / 2 pi: an excitation at the nominal speed within
``RESONANCE_BAND`` of f_d, whose gain there reaches ``WARN_AMPLIFICATION``, is warned. The gain is the damped chain's
frequency response at f_d (not a modal estimate): (K - w^2 J + i w C) x = b, with b the harmonic torque on its body
(gain J_b w^2 |x_b| over the torque: the body's inertia torque) or a mesh's error force k_c L_c^T e (gain
|R_c x| / e: the mesh's force over its blocked error force k_c e); a shaft order, the largest over its meshes. A
planetary stage's phased mesh orders are left to the modes (their phases are the modes' analysis).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from gearcli.core.memo import remember
from gearcli.model.damping import body_matrices, decay_rate, lever_matrices, state_matrix

if TYPE_CHECKING:
    from gearcli.model.assembly import Layout
    from gearcli.model.modes import Resonance

SAME = 1e-9  # an eigenvalue whose Im lies within this fraction of a mode's damped frequency is that mode's


def unmatched_eigenvalues(J: np.ndarray, K: np.ndarray, C: np.ndarray, taken: np.ndarray,
                          natural: np.ndarray, band: float) -> list[complex]:
    """The damped oscillating eigenvalues of the chain (J, K, C) whose Im lambda is none of the modes' damped
    frequencies ``taken`` (rad/s; NaN for a mode without one) and lies farther than ``band`` from every undamped
    frequency ``natural`` (rad/s; an excitation there is checked against that mode), slowest first. An undamped
    eigenvalue (:func:`gearcli.model.damping.decay_rate` 0: its round-off) is left out: its mode stands for it, if
    the solvers' round-off differs (a stiff chain's soft mode is refined from its compliance side)."""
    taken = taken[np.isfinite(taken)]
    lam = np.linalg.eigvals(state_matrix(J, K, C))
    return sorted((complex(z) for z in lam if z.imag > 0.0 and decay_rate(complex(z)) > 0.0
                   and not any(abs(z.imag - w) <= SAME * w for w in taken)
                   and not any(abs(z.imag - w) <= band * z.imag for w in natural)), key=lambda z: z.imag)


def unmatched_resonances(lay: Layout, boundary: str, taken: np.ndarray, natural: np.ndarray, k: np.ndarray,
                         cd: np.ndarray, first: int, f_in: float, kept: dict | None = None,
                         key: bytes | None = None) -> list[Resonance]:
    """The resonance warnings of the damped modes no mode stands for (module text): ``taken`` the modes' damped
    frequencies and ``natural`` their undamped ones (rad/s, NaN for none), ``k``, ``cd`` the connectors' tangents,
    ``first`` the first free body, ``f_in`` the input body's rotation frequency (Hz). ``kept``, ``key``: where the
    chain's matrices and unmatched eigenvalues are kept and under what (the caller's memo of one chain, keyed by
    the bodies' damping: a speed sweep's points share them; the speed enters only the excitations' frequencies)."""
    from gearcli.model.modes import (  # lazy: modes imports this module inside resonances()
        RESONANCE_BAND,
        WARN_AMPLIFICATION,
        Crossing,
        Resonance,
        excitation_sources,
        torque_sources,
    )

    found = kept.get(key) if kept is not None and key is not None else None
    if found is None:
        J, K, C = body_matrices(lay, k, cd, first)
        natural = np.asarray(natural, dtype=float)
        found = (J, K, C, *lever_matrices(lay, first),
                 unmatched_eigenvalues(J, K, C, np.asarray(taken, dtype=float), natural[natural > 0.0],
                                       RESONANCE_BAND))
        if kept is not None and key is not None:
            remember(kept, key, found, cap=8)
    J, K, C, R, L, eigenvalues = found
    out: list[Resonance] = []
    for z in eigenvalues:
        w = z.imag
        f_d, zeta = w / (2.0 * math.pi), -z.real / abs(z)
        dynamic = K - w * w * np.diag(J) + 1j * w * C
        if np.linalg.cond(dynamic) > 1.0 / np.finfo(float).eps:
            continue  # Im lambda of a damped eigenvalue: the response there is finite; singular only by round-off
        sources: list[tuple[str, float, float, int | None, str]] = []  # name, Hz, gain, stage, source
        for o in excitation_sources(lay):
            if not o.phased:
                gain = max((abs(R[c] @ np.linalg.solve(dynamic, k[c] * L[c])) for c in o.via), default=0.0)
                sources.append((f"{o.name} order", o.hz_per_input_hz * f_in, gain, o.stage, o.source))
        for t in torque_sources(lay):
            if t.body >= first:
                b = t.body - first
                x = np.linalg.solve(dynamic, np.eye(J.size)[b])
                fe = t.fixed_Hz if t.fixed_Hz is not None else t.hz_per_input_hz * f_in
                sources.append((t.name, fe, J[b] * w * w * abs(x[b]), None, t.source))
        for name, fe, gain, stage, source in sources:
            if abs(fe - f_d) > RESONANCE_BAND * f_d or gain < WARN_AMPLIFICATION:
                continue
            strength = Crossing(name, 0.0, None, 0.0, gain).strength
            where = "at every speed" if source == "load_fluctuation" else "at the nominal input speed"
            msg = (f"resonance: the {name} ({fe:.4g} Hz {where}) lies within "
                   f"{100 * abs(fe - f_d) / f_d:.2g} % of a damped mode ringing at {f_d:.4g} Hz ({boundary}, "
                   f"{100 * zeta:.2g} % damping) that no undamped mode stands for (strong damping at a body, as a "
                   f"motor's slip damping, holds it still); {strength} excited: the damped chain's response there ≈ "
                   f"{gain:.2g}x the excitation's " + ("harmonic torque" if stage is None and source != "shaft"
                                                        else "blocked error force"))
            out.append(Resonance(None, f_d, "", math.nan, name.removesuffix(" order"), fe, msg, math.nan, gain, zeta,
                                 strength, stage, source))
    return out
