"""The sampling error of the window's mean and std of F_t: what the output samples' rules miss of the integral.

The mean is the trapezoid rule over the samples; its error estimate is Richardson's, |T_h - T_2h| / 3, with
T_2h the rule with every other sample left out (:func:`mean_error`; :mod:`gearcli.simulate.sampling`, "The mean").

The std is the samples' (about their plain mean). For a force the samples resolve it is the std of the
continuous force to the samples' spread of phases; where the samples see a periodic force at few fixed phases
(locked to an excitation's period, a few samples a period), it is the std of those phases, not of the force: a
harmonic at the samples' Nyquist frequency (the second at 4 samples a mesh period) is read as a constant
alternation of its value at the samples' phase, anything between A²/2 and 0 of its A²/2 of variance. A
resolved std does not change when every other sample is left out (each half samples the same force at half the
rate); a std that does is not resolved. The estimate is the larger change of the two halves (even and odd
samples), with no Richardson division: its error is not a power of h where the samples lock (an unloaded mesh
under a 2 µm transmission error sampled 4 times a 500 Hz mesh period read 106.0 N against the force's 85.17 N;
the halves read 149.6 N and 1.4 N). A periodic window (64 samples a period of its fastest excitation) is
not estimated, as its mean is not.
"""

from __future__ import annotations

import numpy as np

RICHARDSON = 3.0  # 2^2 - 1: the trapezoid rule's T_h - T_2h over its error where it is O(h^2) (module doc)
MIN_SAMPLES = 5  # fewer and neither estimate is made (the halves' std needs a few samples each)


def mean_error(t: np.ndarray, x: np.ndarray) -> float:
    """The sampling error of the trapezoid-rule mean of ``x`` over the window ``t`` (module doc):
    Richardson's |T_h - T_2h| / 3, T_2h the rule with every other sample left out (the last sample kept); 0 on fewer
    than 5 samples."""
    n = x.size
    span = float(t[-1] - t[0]) if n else 0.0
    if n < MIN_SAMPLES or not span > 0.0:
        return 0.0
    keep = np.arange(0, n, 2)
    if keep[-1] != n - 1:
        keep = np.append(keep, n - 1)
    whole = float(np.trapezoid(x, t)) / span
    coarse = float(np.trapezoid(x[keep], t[keep])) / span
    return abs(whole - coarse) / RICHARDSON


def std_error(x: np.ndarray, std: float | None = None) -> float:
    """The sampling error of the samples' std of ``x`` (module doc): the larger change of it when every other sample
    is left out (the even samples, the odd ones); 0 on fewer than 5 samples. ``std``: ``x.std()`` when the caller
    has it."""
    if x.size < MIN_SAMPLES:
        return 0.0
    whole = float(x.std()) if std is None else std
    return max(abs(whole - float(x[0::2].std())), abs(whole - float(x[1::2].std())))
