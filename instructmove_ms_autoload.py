"""Register InstructMove-MS with ManiSkill in processes that import ManiSkill.

Gymnasium 1.x has no plugin entry points, so ManiSkill's own commands
(``python -m mani_skill.examples.demo_random_action -e PickCategory-InstructMove``,
``python -m mani_skill.trajectory.replay_trajectory`` and its spawned workers) would not see
our env ids. The installed ``instructmove_ms.pth`` imports this module at interpreter
start-up. It only adds a meta-path finder that waits for ``mani_skill.envs``; when that
module has finished loading, it imports ``instructmove_ms`` (which registers every env and
agent) and removes itself. Processes that never import ManiSkill pay one tiny import.

Set ``INSTRUCTMOVE_NO_AUTOLOAD=1`` to disable the hook.
"""

import os
import sys

_TRIGGER = "mani_skill.envs"


class _AfterManiSkillEnvs:
    """Meta-path finder that wraps the loader of ``mani_skill.envs``."""

    def find_spec(self, fullname, path=None, target=None):
        if fullname != _TRIGGER:
            return None
        sys.meta_path.remove(self)
        from importlib.util import find_spec

        spec = find_spec(fullname)
        if spec is None or spec.loader is None:
            return spec
        exec_module = spec.loader.exec_module

        def exec_then_register(module):
            exec_module(module)
            try:
                import instructmove_ms  # noqa: F401  (registers envs and agents)
            except Exception as exc:  # never break ManiSkill itself
                import warnings

                warnings.warn(f"instructmove_ms could not be registered: {exc!r}", stacklevel=2)

        spec.loader = _Loader(spec.loader, exec_then_register)
        return spec


class _Loader:
    def __init__(self, loader, exec_module):
        self._loader = loader
        self.exec_module = exec_module

    def create_module(self, spec):
        return self._loader.create_module(spec)

    def __getattr__(self, name):
        return getattr(self._loader, name)


def install() -> None:
    """Add the hook unless disabled or ManiSkill's envs are already loaded."""
    if os.environ.get("INSTRUCTMOVE_NO_AUTOLOAD"):
        return
    if _TRIGGER in sys.modules:
        import instructmove_ms  # noqa: F401

        return
    if not any(isinstance(f, _AfterManiSkillEnvs) for f in sys.meta_path):
        sys.meta_path.insert(0, _AfterManiSkillEnvs())
