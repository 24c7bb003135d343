"""Test-session set-up that must happen before numpy is imported.

scipy's Runge-Kutta steps combine the stages with ``numpy.dot``, which OpenBLAS dispatches to a kernel
chosen for the CPU; kernels sum in different orders, so the last bit of a step differs between machines
and a rattling mesh (sensitive to its last bit) can take other steps. The golden check
(``tests/golden``) and the step-for-step engine tests compare integer step counts, so the suite pins
one x86-64 kernel (Haswell: AVX2 + FMA, present on every x86-64 CPU of the last decade) unless the
caller chose one. Subprocesses started by the tests inherit it. The product itself does not pin it.
"""

from __future__ import annotations

import os
import platform


def _x86_with_avx2() -> bool:
    if platform.machine().lower() not in ("x86_64", "amd64"):
        return False
    try:
        with open("/proc/cpuinfo", encoding="ascii", errors="replace") as f:
            flags = next((line for line in f if line.startswith("flags")), "")
    except OSError:
        return False
    return " avx2" in flags and " fma" in flags


if "OPENBLAS_CORETYPE" not in os.environ and _x86_with_avx2():
    os.environ["OPENBLAS_CORETYPE"] = "Haswell"
