"""InstructMove-MS: text-indispensable language-conditioned manipulation for ManiSkill3.

Importing the package registers every env (``PickCategory-InstructMove``, ...) and robot
(``franka``) with ManiSkill and gymnasium.
"""

from pathlib import Path

__version__ = "1.0.0"

# In a source checkout, agents/, tasks/ and assets/ sit next to this folder; setuptools maps
# them into the package on install. Make a plain checkout on sys.path behave the same way.
_checkout = Path(__file__).resolve().parent.parent
if (_checkout / "setup.cfg").is_file() and (_checkout / "agents" / "__init__.py").is_file():
    __path__.append(str(_checkout))  # noqa: F821  (module __path__)

from . import agents as agents  # noqa: E402  (registers robots)
from . import tasks as tasks  # noqa: E402  (registers envs)
