#!/usr/bin/env bash
# Set the machine up (idempotent), then run the main job on the embedded default assets:
# print an episode spec and record a random-action PickCategory episode with ManiSkill's own
# demo command (video under ${OUT:-out/quickstart}).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
bash scripts/setup.sh
py="${PYTHON:-python3}"
out="${OUT:-out/quickstart}"
mkdir -p "$out"
instructmove envs
instructmove episode --task PickCategory-InstructMove --seed 0 --no-render > "$out/episode_seed0.json"
echo "episode spec of seed 0: $out/episode_seed0.json"
"$py" -m mani_skill.examples.demo_random_action -e PickCategory-InstructMove -o rgb \
  --record-dir "$out" --quiet
echo "video: $(ls "$out"/*.mp4)"
