#!/usr/bin/env bash
# The portability tests (pytest -m portability: asset identity, stored held-out episodes,
# sampled episodes, the recorded step reference) under the floating-point set-ups that
# differ in the last bits: OpenBLAS choosing its kernel for this CPU with torch's widest
# kernels (AVX-512 where the CPU has it), an FMA kernel with torch's AVX2 kernels (Haswell),
# a kernel without FMA (Sandybridge) and numpy with every optional CPU feature turned off,
# both with torch's default kernels (ATEN_CPU_CAPABILITY). Each run compares this machine
# with the references recorded on another one; pytest's header names the CPU and kernels.
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
# torch's widest kernels where this CPU has them (AVX-512), else its own choice.
widest="$(ATEN_CPU_CAPABILITY=avx512 "$py" -c \
  'import torch; print(torch.backends.cpu.get_cpu_capability().lower())' 2>/dev/null)" || widest=""
[ "$widest" = avx512 ] || widest=""
run "OpenBLAS's own kernel for this CPU, torch's ${widest:-own} kernels" -u OPENBLAS_CORETYPE \
  ${widest:+ATEN_CPU_CAPABILITY=$widest}
run "an FMA kernel, torch's AVX2 kernels" OPENBLAS_CORETYPE=Haswell ATEN_CPU_CAPABILITY=avx2
run "a kernel without FMA, torch's default kernels" OPENBLAS_CORETYPE=Sandybridge \
  ATEN_CPU_CAPABILITY=default
run "numpy without optional CPU features (${optional:-none here}), torch's default kernels" \
  -u OPENBLAS_CORETYPE NPY_DISABLE_CPU_FEATURES="$optional" ATEN_CPU_CAPABILITY=default
echo "[portability] the same results under every set-up"
