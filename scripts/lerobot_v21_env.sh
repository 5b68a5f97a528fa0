#!/usr/bin/env bash
# An isolated environment with PyPI's lerobot 0.3.3, the release line that reads and writes
# LeRobot v2.1 (the format openpi's training and GR00T read), in which the tests load our
# v2.1 exports the way openpi's data loader does.
#
#   scripts/lerobot_v21_env.sh [VENV]   # default .cache/lerobot-v21-env; a second run does nothing
#
# It is a thin layer over the lerobot 0.4.4 environment (scripts/lerobot_env.sh, built first):
# its own site-packages hold lerobot 0.3.3 and datasets 3.6.0 (lerobot 0.3 needs
# datasets<=3.6), and a .pth file adds the base environment's packages (torch, torchvision,
# torchcodec with its FFmpeg, PyAV, huggingface-hub, ...) after them, so the layer costs a few
# MB instead of another 5 GB. lerobot 0.3.3 asks for torch<2.8; its dataset code runs on the
# base's torch 2.14.1.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
venv="$(realpath -m "${1:-$root/.cache/lerobot-v21-env}")"
base="$root/.cache/lerobot-env"
py="${PYTHON:-python3}"
check() {
  "$venv/bin/python" -c 'import datasets, lerobot.datasets.lerobot_dataset as d; assert d.CODEBASE_VERSION == "v2.1" and datasets.__version__ == "3.6.0"' >/dev/null 2>&1
}
bash "$root/scripts/lerobot_env.sh" "$base"
if [ -x "$venv/bin/python" ] && check; then
  echo "[lerobot-v21-env] ready: $venv"; exit 0
fi
echo "[lerobot-v21-env] building $venv over $base"
rm -rf "$venv"
"$py" -m venv "$venv"
purelib() { "$1" -c 'import sysconfig; print(sysconfig.get_paths()["purelib"])'; }
purelib "$base/bin/python" > "$(purelib "$venv/bin/python")/lerobot_env_base.pth"
PIP_ROOT_USER_ACTION=ignore "$venv/bin/pip" install --quiet --disable-pip-version-check \
  --no-deps lerobot==0.3.3 datasets==3.6.0
check || { echo "[lerobot-v21-env] lerobot 0.3.3 does not import in $venv" >&2; exit 1; }
echo "[lerobot-v21-env] ready: $venv"
