#!/usr/bin/env bash
# Make a Debian/Ubuntu machine ready for InstructMove-MS, then install the package.
#
#   scripts/setup.sh          # runtime install (editable)
#   scripts/setup.sh --dev    # plus test and lint tools
#
# Steps, each skipped when already satisfied (a second run changes nothing):
#   1. PyTorch (CPU build pinned first, so that no CUDA wheels are pulled on a CPU machine);
#   2. the package itself (pip install -e .), re-run only when the packaging files change;
#   3. a Vulkan driver SAPIEN accepts: Mesa lavapipe >= 24.3 when no GPU driver renders.
# Steps 1 and 2 install with the exact versions of constraints.txt (made by scripts/lock.sh),
# the torch already installed (or asked for) taking the place of its torch pin; on a Python
# other than the one the file was made for, they install without it.
# Environment: PYTHON (interpreter, default python3), INSTRUCTMOVE_TORCH (torch version,
# default constraints.txt's).
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
py="${PYTHON:-python3}"
lock="$root/constraints.txt"
[ -f "$lock" ] || { echo "setup.sh: $lock is missing (scripts/lock.sh writes it)" >&2; exit 1; }
locked_torch="$(sed -n 's/^torch==//p' "$lock")"
torch_version="${INSTRUCTMOVE_TORCH:-$locked_torch}"
extras=""
for arg in "$@"; do
  case "$arg" in
    --dev) extras="[dev]" ;;
    *) echo "setup.sh: unknown option '$arg' (allowed: --dev)" >&2; exit 2 ;;
  esac
done

log() { printf '[setup] %s\n' "$*"; }
as_root() { if [ "$(id -u)" = 0 ]; then "$@"; else sudo "$@"; fi; }
pip_install() { PIP_ROOT_USER_ACTION=ignore "$py" -m pip install --quiet --disable-pip-version-check "$@"; }
dist_version() { "$py" -c "import importlib.metadata as m; print(m.version('$1'))" 2>/dev/null; }

# The pins: constraints.txt, its torch line following the torch this machine has or gets.
stamp_dir="$root/.cache"
torch_installed="$(dist_version torch)" || torch_installed=""
torch_now="${torch_installed:-$torch_version}"
torch_now="${torch_now%%+*}"  # 2.13.0+cpu meets torch==2.13.0
lock_py="$(sed -n 's/^# Python \([0-9][0-9.]*\) on .*/\1/p' "$lock")"
this_py="$("$py" -c 'import sys; print("%d.%d" % sys.version_info[:2])')"
if [ "$lock_py" != "$this_py" ]; then
  log "constraints.txt is for Python $lock_py, this is $this_py: installing without it"
  pins=()
elif [ "$torch_now" = "$locked_torch" ]; then
  pins=("$lock")
else
  log "torch $torch_now where constraints.txt has $locked_torch: the other pins still apply"
  mkdir -p "$stamp_dir"
  sed "s/^torch==.*/torch==$torch_now/" "$lock" > "$stamp_dir/constraints-torch.txt"
  pins=("$stamp_dir/constraints-torch.txt")
fi
constrain=()
[ "${#pins[@]}" = 0 ] || constrain=(-c "${pins[0]}")

# 1. PyTorch --------------------------------------------------------------------------
if [ -n "$torch_installed" ]; then
  log "torch $torch_installed already installed"
else
  log "installing torch==$torch_version"
  pip_install "${constrain[@]}" "torch==$torch_version"
fi

# 2. The package ----------------------------------------------------------------------
stamp="$stamp_dir/setup-${extras:-[runtime]}.stamp"
want="$(cat pyproject.toml setup.cfg "${pins[@]}" | sha256sum | cut -d' ' -f1) $("$py" -c 'import sys; print(sys.prefix)')"
installed_here() {
  (cd / && "$py" -c "import importlib.util as u, sys; s = u.find_spec('instructmove_ms'); sys.exit(not (s and s.origin.startswith('$root/')))") \
    >/dev/null 2>&1
}
if [ -f "$stamp" ] && [ "$(cat "$stamp")" = "$want" ] && installed_here; then
  log "instructmove-ms already installed (packaging unchanged)"
else
  log "installing instructmove-ms$extras (editable${pins:+, pinned by ${pins[0]#"$root/"}})"
  pip_install "${constrain[@]}" -e ".$extras"
  mkdir -p "$stamp_dir"
  printf '%s' "$want" > "$stamp"
fi

# 3. Vulkan for SAPIEN ----------------------------------------------------------------
renders() { "$py" -c "import sapien.render as r; r.get_device_summary()" >/dev/null 2>&1; }

add_debian_backports() {
  # Derive the backports entry from the machine's own Debian source (no host is hard-coded).
  local codename="$1" src="/etc/apt/sources.list.d/debian.sources"
  local out="/etc/apt/sources.list.d/instructmove-backports.sources"
  [ -f "$out" ] && return 0
  if [ -f "$src" ]; then
    awk -v cn="$codename" -v RS= -v ORS="\n\n" '
      $0 ~ ("Suites:[^\n]*" cn "([ \n]|$)") && $0 !~ /security/ && !done {
        gsub(/Suites:[^\n]*/, "Suites: " cn "-backports"); print; done=1 }' "$src" | as_root tee "$out" >/dev/null
  elif [ -f /etc/apt/sources.list ]; then
    grep -E "^deb [^ ]+ $codename main" /etc/apt/sources.list | head -n 1 \
      | sed -E "s/ $codename main.*/ $codename-backports main/" \
      | as_root tee /etc/apt/sources.list.d/instructmove-backports.list >/dev/null
  fi
  if [ ! -s "$out" ] && [ ! -s /etc/apt/sources.list.d/instructmove-backports.list ]; then
    echo "setup.sh: could not derive a $codename-backports source from the apt sources" >&2
    exit 1
  fi
}

if renders; then
  log "SAPIEN finds a rendering device"
else
  . /etc/os-release
  log "no rendering device: installing Mesa's Vulkan drivers (lavapipe)"
  export DEBIAN_FRONTEND=noninteractive
  if [ "${ID:-}" = debian ] && [ "${VERSION_CODENAME:-}" = bookworm ]; then
    add_debian_backports bookworm
    as_root apt-get update -qq
    as_root apt-get install -y -qq -t bookworm-backports mesa-vulkan-drivers libvulkan1 >/dev/null
  else
    as_root apt-get update -qq
    as_root apt-get install -y -qq mesa-vulkan-drivers libvulkan1 >/dev/null
  fi
  if ! renders; then
    echo "setup.sh: SAPIEN still finds no rendering device; it needs Mesa >= 24.3 or a GPU driver." >&2
    exit 1
  fi
  log "SAPIEN renders with: $("$py" -c 'import sapien.render as r; print(r.get_device_summary())' 2>/dev/null | head -n 3)"
fi
log "ready"
