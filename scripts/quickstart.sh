#!/usr/bin/env bash
# Set the machine up (idempotent), then run the main job on the embedded default assets:
# planned demos for every family, one trajectory exported to MCAP, the reference policies
# evaluated side by side on a held-out slice, a report and videos (under ${OUT:-out/quickstart};
# a re-run resumes).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
bash scripts/setup.sh
out="${OUT:-out/quickstart}"
instructmove envs
instructmove quickstart --out "$out"
