"""``instructmove doctor``: what works on this machine, one line per finding.

Each check returns its status and one line (a ``Result``), which :func:`run_checks` names as a
:class:`Finding`; a check that raises becomes a failed finding with the exception's text. A
failed *core* finding (the packages, physics on the CPU, rendering, the asset library, the
stored sets) makes the exit status non-zero; the rest (CUDA, GPU physics, optional extras)
only report.
"""

from __future__ import annotations

import importlib.metadata
import importlib.util
import platform
import time
from collections.abc import Callable
from dataclasses import asdict, dataclass
from pathlib import Path

#: The packages the core needs (distribution names).
CORE_PACKAGES = ("instructmove-ms", "mani-skill", "sapien", "torch", "numpy", "gymnasium", "ompl")
#: The optional extras and the module each needs.
EXTRAS = {
    "serve": "openpi_server",
    "ray": "ray",
    "vla-eval": "vla_eval",
    "groot": "zmq",
}
#: The isolated lerobot environments the tests build in a checkout (scripts/lerobot_env.sh,
#: scripts/lerobot_v21_env.sh).
LEROBOT_ENVS = {"lerobot 0.4.4 (v3.0)": "lerobot-env", "lerobot 0.3.3 (v2.1)": "lerobot-v21-env"}
RENDER_SIZE = 128  # pixels a side of the timed test render
#: What a check finds: its status (``ok``, ``warn``, ``fail``) and one line of detail.
Result = tuple[str, str]


@dataclass(frozen=True)
class Finding:
    """One line of the report: ``status`` is ``ok``, ``warn`` or ``fail``."""

    name: str
    status: str
    detail: str
    core: bool = False

    def line(self) -> str:
        return f"{self.status:4} {self.name}: {self.detail}"


def _versions() -> Result:
    found, missing = [], []
    for name in CORE_PACKAGES:
        try:
            found.append(f"{name} {importlib.metadata.version(name)}")
        except importlib.metadata.PackageNotFoundError:
            missing.append(name)
    python = f"Python {platform.python_version()} on {platform.system()} {platform.machine()}"
    if missing:
        return "fail", f"missing: {', '.join(missing)} ({python})"
    return "ok", f"{python}; {', '.join(found)}"


def _floats() -> Result:
    from .floats import describe

    return "ok", describe()


def _physics() -> Result:
    import gymnasium as gym
    import torch

    import instructmove_ms  # noqa: F401  (registration)

    start = time.perf_counter()
    env = gym.make("PickCategory-InstructMove", obs_mode="state", render_backend="none")
    env.reset(seed=0)
    for _ in range(10):
        env.step(torch.zeros(env.action_space.shape))
    env.close()
    seconds = time.perf_counter() - start
    return "ok", f"PickCategory built, reset, 10 steps in {seconds:.1f} s"


def _render() -> Result:
    import numpy as np
    import sapien
    import sapien.render

    device = sapien.render.get_device_summary().strip().splitlines()
    scene = sapien.Scene()
    scene.set_ambient_light([0.5, 0.5, 0.5])
    builder = scene.create_actor_builder()
    builder.add_box_visual(half_size=[0.1, 0.1, 0.1], material=[0.8, 0.2, 0.2])
    builder.build_kinematic(name="box")
    camera = scene.add_camera("doctor", RENDER_SIZE, RENDER_SIZE, 1.0, 0.01, 10.0)
    camera.set_local_pose(sapien.Pose([-0.6, 0.0, 0.0]))
    scene.update_render()
    camera.take_picture()  # the first picture compiles the pipeline
    start = time.perf_counter()
    for _ in range(3):
        scene.update_render()
        camera.take_picture()
        rgb = camera.get_picture("Color")
    ms = (time.perf_counter() - start) / 3 * 1000
    if not np.any(rgb[..., 0] > rgb[..., 1] + 0.2):
        return "fail", "a test render shows nothing (a red box expected)"
    # The summary lists devices as "GPU: NAME" (or "CPU: NAME") lines.
    names = [line.split(":", 1)[1].strip() for line in device if line.startswith(("GPU:", "CPU:"))]
    name = names[0] if names else device[0]
    kind = "a CPU rasteriser" if "llvmpipe" in name.lower() else "a GPU"
    return "ok", f"{name}, {kind}; a {RENDER_SIZE} x {RENDER_SIZE} picture in {ms:.1f} ms"


def _cuda() -> Result:
    import torch

    if not torch.cuda.is_available():
        return "warn", "no CUDA device (GPU physics and GPU rendering off)"
    names = [torch.cuda.get_device_name(i) for i in range(torch.cuda.device_count())]
    return "ok", f"{len(names)} device(s): {', '.join(names)}"


def _gpu_physics() -> Result:
    from . import gpu_physics

    problem = gpu_physics.problem()
    if problem is not None:
        return "warn", problem
    return "ok", f"{gpu_physics.library_path()} present, CUDA found"


def _assets() -> Result:
    from .assets import load_snapshot

    catalog = load_snapshot()  # hash-checked against the generators on load
    return (
        "ok",
        f"snapshot '{catalog.name}': {len(catalog)} instances, every hash matches",
    )


def _stored_sets() -> Result:
    from . import heldout

    changed = {v: heldout.changed_sets(v) for v in heldout.SET_VERSIONS}
    bad = {v: files for v, files in changed.items() if files}
    if bad:
        listed = "; ".join(f"v{v}: {', '.join(files[:3])}" for v, files in bad.items())
        return "fail", f"differ from their checksums: {listed}"
    versions = ", ".join(f"v{v}" for v in heldout.SET_VERSIONS)
    return (
        "ok",
        f"{versions} match their checksums (v{heldout.SET_VERSION} default)",
    )


def _extras() -> Result:
    have = [name for name, module in EXTRAS.items() if importlib.util.find_spec(module)]
    lacking = [name for name in EXTRAS if name not in have]
    detail = f"installed: {', '.join(have) or 'none'}"
    if lacking:
        detail += f"; not installed: {', '.join(lacking)} (pip install 'instructmove-ms[NAME]')"
    return "ok", detail


def _lerobot_envs() -> Result:
    cache = Path(__file__).resolve().parent.parent / ".cache"
    present = [name for name, folder in LEROBOT_ENVS.items() if (cache / folder / "bin").is_dir()]
    if not present:
        return "ok", "none built (scripts/lerobot_env.sh builds them)"
    return "ok", f"{', '.join(present)} in {cache}"


def _workers() -> Result:
    from .executor import cores, share_of_cores

    n = cores()
    return "ok", (
        f"{n} cores; a job runs in one process unless --workers N, each of N workers "
        f"with its share of the cores ({share_of_cores(n)} thread(s) at N = {n})"
    )


#: What to do about a known error, after its text.
HINTS = {
    "failed to find a rendering device": (
        " (SAPIEN needs a Vulkan device even without cameras, its URDF loader makes render "
        "materials: Mesa's lavapipe >= 24.3 or a GPU driver; scripts/setup.sh installs lavapipe)"
    ),
}
#: (name, core, check) in report order.
CHECKS: tuple[tuple[str, bool, Callable[[], Result]], ...] = (
    ("packages", True, _versions),
    ("floating point", False, _floats),
    ("cpu physics", True, _physics),
    ("rendering", True, _render),
    ("cuda", False, _cuda),
    ("gpu physics", False, _gpu_physics),
    ("asset library", True, _assets),
    ("stored sets", True, _stored_sets),
    ("extras", False, _extras),
    ("lerobot environments", False, _lerobot_envs),
    ("workers", False, _workers),
)


def run_checks(only: tuple[str, ...] | None = None) -> list[Finding]:
    """Every check's finding in order (``only``: the checks of those names)."""
    findings = []
    for name, core, check in CHECKS:
        if only is not None and name not in only:
            continue
        try:
            status, detail = check()
        except Exception as exc:  # a broken machine is what the doctor reports
            text = (str(exc).strip().splitlines() or [""])[0]
            hint = next((h for error, h in HINTS.items() if error in text), "")
            status, detail = "fail", f"{type(exc).__name__}: {text}{hint}"
        findings.append(Finding(name, status, detail, core))
    return findings


def broken(findings: list[Finding]) -> list[Finding]:
    """The failed core findings (non-empty: the exit status is non-zero)."""
    return [f for f in findings if f.core and f.status == "fail"]


def as_json(findings: list[Finding]) -> dict:
    return {"ok": not broken(findings), "findings": [asdict(f) for f in findings]}
