"""What decides the last bits of this machine's floating point: the CPU (its vendor's
approximate reciprocals in PhysX's contact generation), the BLAS kernel numpy runs, numpy's
disabled CPU features and the kernels torch dispatches to (see docs/machines.md, "The same
benchmark on every machine")."""

from __future__ import annotations

import ctypes
import glob
import os
import platform
from pathlib import Path


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


def cpu_model() -> str:
    """The CPU: its vendor, family and model and its model name (``/proc/cpuinfo``), with
    whether it has AVX-512, e.g. ``AuthenticAMD 25/17 AMD EPYC, AVX-512``."""
    try:
        first = Path("/proc/cpuinfo").read_text(encoding="utf-8").split("\n\n")[0]
    except OSError:
        return platform.processor() or platform.machine()
    fields = {
        key.strip(): value.strip()
        for key, _, value in (line.partition(":") for line in first.splitlines())
    }
    flags = fields.get("flags", "").split()
    wide = "AVX-512" if "avx512f" in flags else "AVX2" if "avx2" in flags else "no AVX2"
    family = f"{fields.get('cpu family', '?')}/{fields.get('model', '?')}"
    return f"{fields.get('vendor_id', '?')} {family} {fields.get('model name', '')}, {wide}"


def torch_capability() -> str:
    """The CPU kernels torch dispatches to (``ATEN_CPU_CAPABILITY`` forces one), or
    ``no torch``."""
    try:
        import torch
    except ImportError:
        return "no torch"
    return torch.backends.cpu.get_cpu_capability()


def describe() -> str:
    """The CPU, numpy's version, its BLAS kernel, the CPU features turned off and torch's
    dispatch, in one line."""
    import numpy as np

    disabled = os.environ.get("NPY_DISABLE_CPU_FEATURES", "") or "none"
    return (
        f"CPU {cpu_model()}; numpy {np.__version__}, BLAS kernel {blas_kernel()}, "
        f"CPU features off: {disabled}; torch kernels {torch_capability()}"
    )
