#!/usr/bin/env bash
# Write constraints.txt: the exact versions of instructmove-ms[dev] and everything it needs,
# read from the current environment (the one scripts/setup.sh --dev made).
#
#   scripts/lock.sh            # rewrite constraints.txt
#   scripts/lock.sh --check    # exit 1 if constraints.txt differs from what it would write
#
# Method: `pip freeze --all --exclude-editable` gives the versions; the names kept are the
# dependency closure of pyproject.toml's dependencies plus its dev extra, walked through the
# installed distributions' metadata (requirement markers evaluated for this interpreter and
# the extras asked for). It fails when an installed version falls outside a bound on the
# way (run scripts/setup.sh --dev first). Local version labels are dropped (torch
# 2.13.0+cpu is written torch==2.13.0, which pip matches against the local CPU wheel and the
# CUDA builds alike). The same environment always gives the same file.
# Environment: PYTHON (interpreter, default python3).
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
py="${PYTHON:-python3}"
check=0
for arg in "$@"; do
  case "$arg" in
    --check) check=1 ;;
    *) echo "lock.sh: unknown option '$arg' (allowed: --check)" >&2; exit 2 ;;
  esac
done

freeze="$(PIP_DISABLE_PIP_VERSION_CHECK=1 "$py" -m pip freeze --all --exclude-editable)"
new="$(FREEZE="$freeze" "$py" - "$root/pyproject.toml" <<'EOF'
import importlib.metadata as md
import os
import platform
import re
import sys
import tomllib

try:
    from packaging.requirements import Requirement
    from packaging.version import Version
except ImportError:  # pip always carries a copy
    from pip._vendor.packaging.requirements import Requirement
    from pip._vendor.packaging.version import Version


def canon(name: str) -> str:
    return re.sub(r"[-_.]+", "-", name).lower()


frozen = {}
for line in os.environ["FREEZE"].splitlines():
    name, sep, version = line.partition("==")
    if sep:
        frozen[canon(name)] = version.strip()

project = tomllib.load(open(sys.argv[1], "rb"))["project"]
roots = [*project["dependencies"], *project.get("optional-dependencies", {}).get("dev", [])]
errors, extras_of, todo = [], {}, [(Requirement(r), "pyproject.toml") for r in roots]
while todo:
    req, parent = todo.pop()
    name = canon(req.name)
    try:
        dist = md.distribution(name)
    except md.PackageNotFoundError:
        errors.append(f"{req} (needed by {parent}) is not installed")
        continue
    if not req.specifier.contains(dist.version, prereleases=True):
        errors.append(f"{name} {dist.version} is outside {req} (needed by {parent})")
    wanted = set(req.extras)
    if name in extras_of and wanted <= extras_of[name]:
        continue
    extras_of[name] = extras_of.get(name, set()) | wanted
    for line in dist.requires or []:
        sub = Requirement(line)
        scopes = [{"extra": e} for e in sorted(extras_of[name] | {""})]
        if sub.marker is None or any(sub.marker.evaluate(s) for s in scopes):
            todo.append((sub, name))
missing = sorted(n for n in extras_of if n not in frozen)
errors += [f"{n} is needed but pip freeze does not list it" for n in missing]
if errors:
    problems = "\n  ".join(sorted(set(errors)))
    sys.exit(f"lock.sh: run scripts/setup.sh --dev first; this environment has:\n  {problems}")
py = f"{sys.version_info.major}.{sys.version_info.minor}"
made = f"{platform.python_implementation()} {platform.python_version()}"
print("# Exact versions of instructmove-ms[dev] and everything it needs, a pip constraints file:")
print("# it pins what an install picks and installs nothing itself. scripts/setup.sh installs")
print('# with it; by hand: pip install -c constraints.txt -e ".[dev]" (torch first).')
print(f"# Python {py} on {sys.platform} {platform.machine()} (other Pythons install without it).")
print(f"# Made by scripts/lock.sh from an environment set up by scripts/setup.sh --dev ({made}):")
print("# pip freeze, kept to the dependency closure of pyproject.toml's dependencies and dev")
print("# extra, local version labels dropped (+cpu). Regenerate with: bash scripts/lock.sh")
for name in sorted(extras_of):
    print(f"{name}=={Version(frozen[name]).public}")
EOF
)"

out="$root/constraints.txt"
if [ "$check" = 1 ]; then
  if [ "$new" = "$(cat "$out" 2>/dev/null)" ]; then
    echo "[lock] constraints.txt is up to date ($(grep -vc '^#' "$out") pins)"
  else
    echo "[lock] constraints.txt differs from this environment:" >&2
    diff <(printf '%s\n' "$new") "$out" >&2 || true
    exit 1
  fi
else
  printf '%s\n' "$new" > "$out.tmp"
  mv "$out.tmp" "$out"
  echo "[lock] wrote $out ($(grep -vc '^#' "$out") pins)"
fi
