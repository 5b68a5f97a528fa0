#!/usr/bin/env bash
# An isolated environment with cffconvert, the Citation File Format's own validator, with
# which the tests check CITATION.cff (cffconvert 2.0 needs jsonschema < 4, which this
# package's environment does not have). A few MB, seconds.
#
#   scripts/cff_env.sh [VENV]   # default .cache/cff-env; a second run does nothing
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
venv="$(realpath -m "${1:-$root/.cache/cff-env}")"
py="${PYTHON:-python3}"
if [ -x "$venv/bin/cffconvert" ] && "$venv/bin/cffconvert" --version >/dev/null 2>&1; then
  echo "[cff-env] ready: $venv"; exit 0
fi
echo "[cff-env] building $venv"
rm -rf "$venv"
"$py" -m venv "$venv"
PIP_ROOT_USER_ACTION=ignore "$venv/bin/pip" install --quiet --disable-pip-version-check \
  cffconvert==2.0.0 jsonschema==3.2.0
"$venv/bin/cffconvert" --version >/dev/null
echo "[cff-env] ready: $venv"
