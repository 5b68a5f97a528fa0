#!/usr/bin/env bash
# Set the machine up (idempotent) and run the linter and the test suite.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
bash scripts/setup.sh --dev
py="${PYTHON:-python3}"
"$py" -m ruff check .
"$py" -m pytest -q "$@"
