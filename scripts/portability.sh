#!/usr/bin/env bash
# The portability tests (pytest -m portability: asset identity, stored held-out episodes,
# sampled episodes, the recorded step reference) under the floating-point set-ups that
# differ in the last bits: OpenBLAS choosing its kernel for this CPU, an FMA kernel
# (Haswell), a kernel without FMA (Sandybridge), and numpy with every optional CPU feature
# turned off. Each run compares this machine with the references recorded on another one.
#
#   scripts/portability.sh [PYTEST ARGS...]
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
py="${PYTHON:-python3}"
optional="$("$py" - <<'PY'
try:
    from numpy._core._multiarray_umath import __cpu_dispatch__, __cpu_features__
except ImportError:
    from numpy.core._multiarray_umath import __cpu_dispatch__, __cpu_features__
print(" ".join(f for f in __cpu_dispatch__ if __cpu_features__.get(f)))
PY
)"
run() {
  local name="$1"
  shift
  echo "[portability] $name"
  env "$@" "$py" -m pytest -q -m portability -p no:cacheprovider "${extra[@]}"
}
extra=("$@")
run "OpenBLAS's own kernel for this CPU" -u OPENBLAS_CORETYPE
run "an FMA kernel" OPENBLAS_CORETYPE=Haswell
run "a kernel without FMA" OPENBLAS_CORETYPE=Sandybridge
run "numpy without optional CPU features (${optional:-none here})" -u OPENBLAS_CORETYPE \
  NPY_DISABLE_CPU_FEATURES="$optional"
echo "[portability] the same results under every set-up"
