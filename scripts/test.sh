#!/usr/bin/env bash
# Set the machine up (idempotent) and run the linter and the test suite (which loads our
# LeRobot export with the real lerobot in its own environment, built here once). Without
# arguments the portability tests then run again under several BLAS kernels, torch's CPU
# kernels and without numpy's optional CPU features (scripts/portability.sh), even when the
# suite failed (the script still exits non-zero); with arguments, pytest gets them.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
bash scripts/setup.sh --dev
bash scripts/lerobot_env.sh  # the real LeRobot 0.4.4, isolated: loads v3.0, trains, serves
bash scripts/lerobot_v21_env.sh  # lerobot 0.3.3 over it: loads v2.1 as openpi does
bash scripts/cff_env.sh  # cffconvert, isolated: validates CITATION.cff
py="${PYTHON:-python3}"
"$py" -m ruff check .
if [ "$#" -gt 0 ]; then
  "$py" -m pytest -q "$@"
  exit
fi
# The test files run in parallel, one process per core up to 4 (each builds its own scenes;
# PYTEST_WORKERS overrides, 0 runs them in this process).
cores="$(nproc)"
suite=0
"$py" -m pytest -q -m "not portability" -n "${PYTEST_WORKERS:-$((cores < 4 ? cores : 4))}" \
  --dist loadfile --durations=15 || suite=$?
# The portability runs go on after a failed suite (what another CPU gets wrong shows there).
portability=0
bash scripts/portability.sh || portability=$?
if [ "$suite" != 0 ] || [ "$portability" != 0 ]; then
  echo "[test] failed: test suite exit $suite, portability exit $portability" >&2
  exit 1
fi
