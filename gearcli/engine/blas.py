"""numpy's own BLAS, for the kernel's few vector sums: the way to take scipy's steps bit for bit.

scipy's DOP853 forms its stage sums, error estimates and interpolant with ``np.dot`` (BLAS ``dgemv``,
``dgemm``, ``ddot``), whose summation order and fused multiply-adds differ from a plain loop in the last
bit. On a rattling gear train such last-bit differences flip a step decision within a few hundred steps
and the two runs part (measured: 1e-3 to 1 relative on 11 of the 20 non-stiff example scenes). The kernel
therefore calls the very BLAS library numpy is linked against, with the arguments numpy passes (checked
bit for bit against ``np.dot`` by tests/engine), and falls back to plain loops when that library is not
found (another numpy build): the run is then as accurate, but its steps may differ from scipy's in the
last bit.
"""

from __future__ import annotations

import ctypes
import glob
import os

import numpy as np

# (symbol pattern, integer width): scipy-openblas wheels (ILP64 and LP64), then plain OpenBLAS/reference
_PATTERNS = (("scipy_cblas_{}64_", 64), ("cblas_{}64_", 64), ("scipy_cblas_{}", 32), ("cblas_{}", 32))
_FUNCS = ("dgemv", "dgemm", "ddot")


def _candidates() -> list[str]:
    root = os.path.dirname(np.__file__)
    found = []
    for pattern in (root + ".libs/*blas*", root + "/.dylibs/*blas*", root + "/../numpy.libs/*blas*"):
        found += sorted(glob.glob(pattern))
    return found


def find() -> tuple[str, str, int] | None:
    """(library path, symbol pattern, integer width) of numpy's BLAS, or None."""
    for path in _candidates():
        try:
            lib = ctypes.CDLL(path)
        except OSError:
            continue
        for pattern, width in _PATTERNS:
            if all(hasattr(lib, pattern.format(f)) for f in _FUNCS):
                return path, pattern, width
    return None


FOUND = find()
KEY = "none" if FOUND is None else f"{os.path.basename(FOUND[0])}:{FOUND[1]}:{FOUND[2]}"


def register() -> bool:
    """Make the library's symbols visible to numba's linker; False when there is none."""
    if FOUND is None:
        return False
    import llvmlite.binding as llvm  # lazy: llvmlite, numba's (the optional fast extra)

    llvm.load_library_permanently(FOUND[0])
    return True
