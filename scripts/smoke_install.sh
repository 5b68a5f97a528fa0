#!/usr/bin/env bash
# Packaging smoke test: build the wheel from this checkout, install it (not editable) in a
# clean virtual environment and run the package from outside the source tree: the asset
# list, a stored held-out episode reset with rgb cameras, one planned demo and a one-episode
# evaluation of the planner oracle. Prints the versions the install picked.
#
#   scripts/smoke_install.sh [--locked] [VENV]
#
# VENV: where the environment goes (re-created; default: a temporary folder, removed at the
# end). By default the wheel's dependencies are what the resolver picks today (the versions
# the package's bounds let in); --locked (or SMOKE_CONSTRAINTS=1) installs with the exact
# versions of constraints.txt instead. torch goes in first, torch==INSTRUCTMOVE_TORCH
# (default: constraints.txt's), so that pip's configured wheel source (a local CPU build on
# a CPU machine) supplies it rather than a CUDA build from the index.
# Environment: PYTHON (interpreter, default python3), INSTRUCTMOVE_TORCH, SMOKE_CONSTRAINTS.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
py="${PYTHON:-python3}"
locked="${SMOKE_CONSTRAINTS:-0}"
venv=""
for arg in "$@"; do
  case "$arg" in
    --locked) locked=1 ;;
    -*) echo "smoke_install.sh: unknown option '$arg' (allowed: --locked)" >&2; exit 2 ;;
    *) [ -z "$venv" ] || { echo "smoke_install.sh: one VENV only" >&2; exit 2; }; venv="$arg" ;;
  esac
done
lock="$root/constraints.txt"
torch_version="${INSTRUCTMOVE_TORCH:-$(sed -n 's/^torch==//p' "$lock")}"
if [ -z "$torch_version" ]; then
  echo "smoke_install.sh: no torch version (INSTRUCTMOVE_TORCH, constraints.txt)" >&2; exit 1
fi

start=$SECONDS
log() { printf '[smoke] %4ds %s\n' "$((SECONDS - start))" "$*"; }
fail() { printf '[smoke] FAILED after %ds: %s\n' "$((SECONDS - start))" "$*" >&2; exit 1; }
work="$(mktemp -d "${TMPDIR:-/tmp}/instructmove-smoke.XXXXXX")"
trap 'rm -rf "$work"' EXIT
if [ -z "$venv" ]; then
  venv="$work/venv"
else
  venv="$(realpath -m "$venv")"
  if [ -e "$venv" ] && [ ! -f "$venv/pyvenv.cfg" ] && [ -n "$(ls -A "$venv")" ]; then
    fail "$venv exists and is not a virtual environment"
  fi
  rm -rf "$venv"
fi
constrain=()
if [ "$locked" = 1 ]; then
  constrain=(-c "$lock")
  log "mode: locked (constraints.txt), torch==$torch_version"
else
  log "mode: what the resolver picks today, torch==$torch_version"
fi

# 1. The wheel, built from a copy of the checkout's files (tracked or not ignored), so that
#    no build folder of the checkout leaks stale files into it ------------------------------
log "copying the source tree"
"$py" - "$root" "$work/src" <<'EOF'
import shutil
import subprocess
import sys
from pathlib import Path

root, dst = Path(sys.argv[1]), Path(sys.argv[2])
git = ["git", "-C", str(root), "ls-files", "-z", "--cached", "--others", "--exclude-standard"]
try:
    listed = subprocess.run(git, capture_output=True, check=True).stdout.decode()
    names = [n for n in listed.split("\0") if n]
except (OSError, subprocess.CalledProcessError):  # not a git checkout: every file but caches
    caches = (".git", ".cache", "build", "dist", "out", "*.egg-info", "__pycache__")
    shutil.copytree(root, dst, ignore=shutil.ignore_patterns(*caches))
    sys.exit(0)
for name in names:
    if (root / name).is_file():  # a tracked file deleted in the work tree is not shipped
        (dst / name).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(root / name, dst / name)
EOF
log "building the wheel"
"$py" -m pip wheel --quiet --disable-pip-version-check --no-deps -w "$work/dist" "$work/src" \
  || fail "pip wheel"
wheels=("$work"/dist/instructmove_ms-*.whl)
[ "${#wheels[@]}" = 1 ] && [ -f "${wheels[0]}" ] || fail "expected one wheel in $work/dist"
wheel="${wheels[0]}"
"$py" - "$wheel" <<'EOF' || fail "the wheel does not hold what ships"
import sys
import zipfile

names = set(zipfile.ZipFile(sys.argv[1]).namelist())
want = [
    "instructmove_ms.pth",  # written by build_hooks.BuildPyWithPth
    "instructmove_ms_autoload.py",
    "instructmove_ms/cli/__init__.py",
    "instructmove_ms/agents/__init__.py",
    "instructmove_ms/tasks/__init__.py",
    "instructmove_ms/assets/__init__.py",
    "instructmove_ms/assets/taxonomy.yaml",
    "instructmove_ms/assets/snapshots/recognisable.json",
    "instructmove_ms/assets/snapshots/appearance/recognisable.json",
    "instructmove_ms/tasks/episodes/v7/checksums.json",
    "instructmove_ms/tasks/episodes/v7/PickCategory-InstructMove/franka/seen.jsonl",
    "instructmove_ms/tasks/episodes/v8/checksums.json",
    "instructmove_ms/tasks/episodes/v8/PlaceA2B-InstructMove/piperx/unseen_category.jsonl",
]
missing = [n for n in want if n not in names]
if missing:
    sys.exit(f"missing: {missing}")
# the stored sets of InstructMove 1.0 (v7) and 2.0 (v8) and one snapshot ship
sets = {n.split("/")[3] for n in names if n.startswith("instructmove_ms/tasks/episodes/")}
snapshots = {n for n in names if n.startswith("instructmove_ms/assets/snapshots/")}
if sets != {"v7", "v8"} or len(snapshots) != 2:
    sys.exit(f"the wheel holds other stored data: sets {sorted(sets)}, {sorted(snapshots)}")
pth = zipfile.ZipFile(sys.argv[1]).read("instructmove_ms.pth").decode()
if not pth.startswith("import ") or "instructmove_ms_autoload" not in pth:
    sys.exit(f"instructmove_ms.pth does not load the autoload hook: {pth!r}")
wheel = sys.argv[1].rsplit("/", 1)[-1]
print(f"[smoke]        {wheel}: {len(names)} files, instructmove_ms.pth included")
EOF

# 2. A clean virtual environment: torch first, then the wheel -------------------------------
log "creating $venv"
"$py" -m venv "$venv"
vpy="$venv/bin/python"
vpip() { PIP_ROOT_USER_ACTION=ignore "$vpy" -m pip --disable-pip-version-check "$@"; }
# pip's own messages, less its notes on configured index folders that do not exist here
vpip_install() {
  local rc=0
  vpip install --quiet "${constrain[@]}" "$@" 2>"$work/pip.err" || rc=$?
  grep -v "is ignored: it is neither a file nor a directory" "$work/pip.err" >&2 || true
  return "$rc"
}
log "installing torch==$torch_version"
vpip_install "torch==$torch_version" || fail "installing torch"
log "installing the wheel"
vpip_install "$wheel" || fail "installing the wheel"
vpip check >/dev/null || { vpip check >&2; fail "pip check"; }
log "installed versions (pip freeze):"
vpip freeze --all | sed 's/^/[smoke]        /'
if [ "$locked" = 0 ]; then
  vpip freeze --all | "$py" -c '
import re, sys

def pins(lines):
    split = (line.strip().partition("==") for line in lines if not line.startswith("#"))
    return {re.sub(r"[-_.]+", "-", n).lower(): v.split("+")[0] for n, _, v in split if v}

lock, got = pins(open(sys.argv[1])), pins(sys.stdin)
diff = [f"{n} {lock[n]} -> {got[n]}" for n in sorted(lock.keys() & got.keys()) if lock[n] != got[n]]
only_here = sorted(got.keys() - lock.keys() - {"pip"})
diff += [f"{n} {got[n]} (not in constraints.txt)" for n in only_here]
print(f"[smoke]        {len(diff)} differences from constraints.txt:")
for line in diff:
    print(f"[smoke]          {line}")
' "$lock"
fi

# 3. The package at work, from outside the checkout -----------------------------------------
run="$work/run"
mkdir -p "$run"
cd "$run"
export PATH="$venv/bin:$PATH"
unset PYTHONPATH INSTRUCTMOVE_NO_AUTOLOAD PYTHONHOME
hash -r
[ "$(command -v instructmove)" = "$venv/bin/instructmove" ] || fail "instructmove is not the venv's"

log "import: the installed package, every module of it, our envs in ManiSkill's registry"
"$vpy" - "$venv" <<'EOF' 2>import.log || { tail -n 20 import.log >&2; fail "import / autoload"; }
import importlib
import sys
from pathlib import Path

import mani_skill.envs  # noqa: F401  (the .pth hook registers our envs after this import)
from mani_skill.utils.registration import REGISTERED_ENVS

import instructmove_ms

where = Path(instructmove_ms.__file__).resolve()
assert Path(sys.argv[1]).resolve() in where.parents, f"imported from {where}, not the venv"
assert "PickCategory-InstructMove" in REGISTERED_ENVS, "the autoload hook did not register"
names = []
for path in sorted(where.parent.rglob("*.py")):
    parts = path.relative_to(where.parent.parent).with_suffix("").parts
    parts = parts[:-1] if parts[-1] == "__init__" else parts
    if parts[-1] != "__main__":
        names.append(".".join(parts))
from instructmove_ms.integrations import MissingExtra

broken, extras = [], {}
for name in names:
    try:
        importlib.import_module(name)
    except MissingExtra as exc:  # an integration whose optional package is not installed
        extras[name] = str(exc)
    except Exception as exc:  # a dependency missing or built against another ABI
        broken.append(f"{name}: {exc!r}")
assert not broken, "modules that do not import:\n  " + "\n  ".join(broken)
want = {
    "instructmove_ms.integrations.vla_eval": "vla-eval",
    "instructmove_ms.integrations.groot": "groot",
}
assert set(extras) == set(want), f"modules that need an extra: {sorted(extras)}"
for name, extra in want.items():
    assert f"pip install 'instructmove-ms[{extra}]'" in extras[name], extras[name]
print(f"[smoke]        {len(names) - len(extras)} modules of {where.parent} import; "
      f"{len(extras)} name their extra ({', '.join(sorted(want.values()))})")
EOF

log "a GR00T server without pyzmq: one line naming the extra, exit 2"
rc=0
instructmove eval --task PickCategory-InstructMove --robot franka --split seen --episodes 1 \
  --policy zmq://127.0.0.1:9 --obs-format groot --out groot > groot.log 2>&1 || rc=$?
[ "$rc" = 2 ] && [ "$(wc -l < groot.log)" = 1 ] && grep -q "instructmove-ms\[groot\]" groot.log \
  || { cat groot.log >&2; fail "eval --policy zmq:// without pyzmq (exit $rc)"; }

log "instructmove assets list"
instructmove assets list > assets.txt || fail "instructmove assets list"
count="$(grep -cE '^[0-9a-f]{8}-[0-9a-f]{4}-' assets.txt || true)"
[ "$count" -gt 0 ] || fail "instructmove assets list printed no instances"
printf '[smoke]        %s instances listed\n' "$count"

log "reset of a stored held-out episode (PickCategory, franka, seen #0) with rgb cameras"
"$vpy" - <<'EOF' || fail "held-out reset"
import gymnasium as gym

import instructmove_ms  # noqa: F401
from instructmove_ms.heldout import load_set

spec = load_set("PickCategory-InstructMove", "franka", "seen")[0]
env = gym.make(
    "PickCategory-InstructMove", obs_mode="rgb", render_backend="cpu", robot_uids="franka"
)
obs, _ = env.reset(seed=spec.seed, options={"episode": spec.to_dict()})
images = {cam: data["rgb"] for cam, data in obs["sensor_data"].items()}
assert images, "no camera in the observation"
for cam, rgb in images.items():
    assert rgb.numel() > 0 and rgb.shape[-1] == 3, f"{cam}: rgb of shape {tuple(rgb.shape)}"
    assert rgb.float().std() > 0, f"{cam}: a blank image"
said = env.unwrapped.get_language_instruction()
assert said == [spec.instruction], f"instruction {said} != stored {spec.instruction!r}"
rebuilt = [o.uuid for o in env.unwrapped.episode.objects]
assert rebuilt == [o.uuid for o in spec.objects], "the objects differ from the stored episode"
env.close()
shapes = ", ".join(f"{cam} {tuple(rgb.shape[1:])}" for cam, rgb in images.items())
print(f"[smoke]        {spec.instruction!r}; {shapes}")
EOF

log "instructmove demos generate (1 planned demo)"
instructmove demos generate --task PickCategory-InstructMove --robot franka -n 1 --out demos \
  > demos.log 2>&1 || { tail -n 20 demos.log >&2; fail "instructmove demos generate"; }
"$vpy" - <<'EOF' || fail "demo output"
import json
from pathlib import Path

import h5py

stem = Path("demos/PickCategory-InstructMove_franka")
with h5py.File(stem.with_suffix(".h5")) as f:
    assert "traj_0" in f and len(f["traj_0/actions"]) > 0, "no trajectory in the .h5"
shards = json.loads(stem.with_suffix(".ledger.json").read_text())["shards"]
kept = sum(s["kept"] for s in shards)
assert kept == 1, f"the ledger says {kept} demos kept: {shards}"
episodes = json.loads(stem.with_suffix(".json").read_text())["episodes"]
assert [e["success"] for e in episodes] == [True], f"trajectory episodes: {episodes}"
print(f"[smoke]        demo kept ({episodes[0]['elapsed_steps']} steps)")
EOF

log "instructmove eval (planner oracle, 1 stored episode)"
instructmove eval --task PickCategory-InstructMove --robot franka --split seen --policy oracle \
  --episodes 1 --out eval > eval.log 2>&1 || { tail -n 20 eval.log >&2; fail "instructmove eval"; }
"$vpy" - <<'EOF' || fail "eval output"
import json
from pathlib import Path

rows = [json.loads(line) for line in Path("eval/episodes.jsonl").read_text().splitlines() if line]
assert len(rows) == 1, f"{len(rows)} result rows"
assert rows[0]["error"] is None, f"the episode failed: {rows[0]['error']}"
print(f"[smoke]        result row: success={rows[0]['success']}, stages={rows[0]['stages']}")
EOF

log "passed in $((SECONDS - start)) s"
