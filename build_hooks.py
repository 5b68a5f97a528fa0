"""Build step that ships ``instructmove_ms.pth`` at the root of site-packages.

The .pth line runs ``instructmove_ms_autoload.install()`` at interpreter start-up so that
ManiSkill's own commands see our env ids. Works for ``pip install .`` (written into build_lib)
and ``pip install -e .`` (written into the editable wheel's root).
"""

from pathlib import Path

from setuptools.command.build_py import build_py

PTH_NAME = "instructmove_ms.pth"
# One line (site.py runs .pth lines that start with "import"); silent when the package was
# removed without pip (e.g. a deleted editable checkout) instead of failing every start-up.
PTH_LINE = (
    "import importlib.util as _u; "
    "_u.find_spec('instructmove_ms_autoload') and "
    "__import__('instructmove_ms_autoload').install()\n"
)


class BuildPyWithPth(build_py):
    def run(self) -> None:
        super().run()
        if getattr(self, "editable_mode", False):
            target = Path(self.get_finalized_command("install").install_lib)
        else:
            target = Path(self.build_lib)
        target.mkdir(parents=True, exist_ok=True)
        (target / PTH_NAME).write_text(PTH_LINE)
