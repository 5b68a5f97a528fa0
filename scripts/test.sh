#!/usr/bin/env bash
# Set the machine up (idempotent) and run the linter and the test suite (which loads our
# LeRobot export with the real lerobot in its own environment, built here once). Without
# arguments the portability tests then run again under several BLAS kernels and without
# numpy's optional CPU features (scripts/portability.sh); with arguments, pytest gets them.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
bash scripts/setup.sh --dev
bash scripts/lerobot_env.sh  # the real LeRobot 0.4.4, isolated: loads v3.0, trains, serves
bash scripts/lerobot_v21_env.sh  # lerobot 0.3.3 over it: loads v2.1 as openpi does
py="${PYTHON:-python3}"
"$py" -m ruff check .
if [ "$#" -gt 0 ]; then
  "$py" -m pytest -q "$@"
  exit
fi
# The test files run in parallel, one process per core up to 4 (each builds its own scenes;
# PYTEST_WORKERS overrides, 0 runs them in this process).
cores="$(nproc)"
"$py" -m pytest -q -m "not portability" -n "${PYTEST_WORKERS:-$((cores < 4 ? cores : 4))}" \
  --dist loadfile --durations=15
bash scripts/portability.sh
