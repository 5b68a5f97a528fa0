"""Whether GPU physics can start on this machine, asked before ManiSkill asks SAPIEN.

SAPIEN loads PhysX's GPU library from ``~/.sapien/physx/<PhysX version>/`` and, the first time
it is missing, downloads it from the network inside ``sapien.physx.enable_gpu()``; on a
machine without the network (many lab clusters) that fails deep inside ManiSkill's env
constructor. :func:`check_gpu_physics` names the file, the version and the folder instead,
without touching the network, and then asks for a CUDA device.
"""

from __future__ import annotations

import platform
from pathlib import Path

#: ManiSkill's names of the simulation backends (``sim_backend``, before a ``:device``).
GPU_BACKENDS = ("gpu", "cuda", "physx_cuda")
#: Where SAPIEN publishes the GPU library, per platform (the archive to unzip in the folder).
RELEASES = "https://github.com/sapien-sim/physx-precompiled/releases/download"
ARCHIVES = {("Linux", "x86_64"): "linux-so.zip", ("Linux", "aarch64"): "linux-aarch64-so.zip"}


class GpuPhysicsUnavailable(RuntimeError):
    """GPU physics cannot start here; the message says what is missing, in one line."""


def uses_gpu_physics(sim_backend: str, num_envs: int) -> bool:
    """Whether ManiSkill runs ``sim_backend`` (``"auto"``: the GPU for more than one env) on
    the GPU."""
    name = sim_backend.split(":")[0]
    return name in GPU_BACKENDS or (name == "auto" and num_envs > 1)


def physx_version() -> str:
    """The PhysX version SAPIEN's GPU library must match (``sapien.physx.version()``)."""
    import sapien.physx

    return sapien.physx.version()


def library_path() -> Path:
    """Where SAPIEN loads PhysX's GPU library from."""
    name = "PhysXGpu_64.dll" if platform.system() == "Windows" else "libPhysXGpu_64.so"
    return Path.home() / ".sapien" / "physx" / physx_version() / name


def library_source() -> str:
    """The archive SAPIEN would download the library from, for this platform."""
    archive = ARCHIVES.get((platform.system(), platform.machine()), "windows-dll.zip")
    return f"{RELEASES}/{physx_version()}/{archive}"


def problem() -> str | None:
    """What keeps GPU physics from starting here (the PhysX GPU library, then CUDA), or None."""
    import sapien.physx

    if sapien.physx.is_gpu_enabled():
        return None
    lib = library_path()
    if not lib.is_file():
        return (
            f"GPU physics needs SAPIEN's PhysX GPU library {lib.name} (PhysX {physx_version()}) "
            f"in {lib.parent}/, which is missing: unzip {library_source()} there (on an offline "
            "machine, copy that folder from one with the network)"
        )
    import torch

    if not torch.cuda.is_available():
        return "GPU physics needs a CUDA device; torch finds none (torch.cuda.is_available())"
    return None


def check_gpu_physics() -> None:
    """Raise :class:`GpuPhysicsUnavailable` where GPU physics cannot start here."""
    found = problem()
    if found is not None:
        raise GpuPhysicsUnavailable(found)
