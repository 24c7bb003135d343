"""The excitation frequencies of a scene at its nominal speed (for periodic steady states and spectra).

A phase-dependent mesh (transmission error, stiffness harmonics, time-varying contact lines) excites at
its mesh frequency ``z_p w_p / 2 pi`` and its integer multiples; an input torque ripple of order n at
n times the input body's rotation frequency; a load fluctuation at its own frequency. The response of a
scene excited only by meshes repeats over the common period of its mesh frequencies (rational multiples
of one another through the tooth counts) when it is periodic at all.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from gearcli.model.assembly import Layout
from gearcli.model.elements.mesh import I_NKS, I_NTE, I_Z


@dataclass(frozen=True)
class Excitation:
    source: str  # "stage 1 mesh", "input torque ripple", "load fluctuation"
    frequency_Hz: float  # fundamental at the nominal speed
    harmonics: int  # highest harmonic present (1 for the torques and time-varying contact lines alone)


def excitations(lay: Layout) -> list[Excitation]:
    """Every excitation of the scene at the nominal input speed (module text)."""
    f_in = lay.drive.speed_rad_s / (2.0 * math.pi)
    out = []
    for k, c in enumerate(lay.stage_conn):
        x = lay.connectors[c]
        if x.phased:
            n = max(int(x.params[I_NTE]), int(x.params[I_NKS]), 1)
            out.append(Excitation(f"stage {k + 1} mesh", x.params[I_Z] * lay.bodies[x.a].ratio * f_in, n))
    for _, order in lay.drive.ripple:
        out.append(Excitation("input torque ripple", order * f_in, 1))
    for _, freq in lay.load.fluctuation:
        out.append(Excitation("load fluctuation", freq, 1))
    return out
