"""What decides the last bits of this machine's floating point: the BLAS kernel numpy runs
and numpy's disabled CPU features (see the README's "The same benchmark on every machine")."""

from __future__ import annotations

import ctypes
import glob
import os


def blas_kernel() -> str:
    """The kernel numpy's OpenBLAS runs here (``OPENBLAS_CORETYPE`` forces one), or
    ``unknown`` for a numpy without its own OpenBLAS."""
    import numpy as np

    libs = os.path.join(os.path.dirname(np.__file__), os.pardir, "numpy.libs", "libopenblas*")
    for path in sorted(glob.glob(libs)):
        lib = ctypes.CDLL(path)
        for name in ("openblas_get_corename64_", "openblas_get_corename"):
            getter = getattr(lib, name, None)
            if getter is not None:
                getter.restype = ctypes.c_char_p
                return getter().decode()
    return "unknown"


def describe() -> str:
    """numpy's version, its BLAS kernel and the CPU features turned off, in one line."""
    import numpy as np

    disabled = os.environ.get("NPY_DISABLE_CPU_FEATURES", "") or "none"
    return f"numpy {np.__version__}, BLAS kernel {blas_kernel()}, CPU features off: {disabled}"
