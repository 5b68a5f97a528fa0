"""On ``PYTHONPATH`` of the isolated LeRobot environment's Python (scripts/lerobot_env.sh), this
appends the directories in ``$INSTRUCTMOVE_BRIDGE_PATH`` to ``sys.path`` after the
environment's own site-packages: lerobot and its torch and numpy come from that environment,
``instructmove_ms``, ManiSkill and SAPIEN (which it lacks) from the checkout and the main
environment. A user installs both in one environment instead; the tests keep LeRobot's pins
out of the main one. Appended, not processed as site directories: no ``.pth`` file of the
main environment runs."""

import os
import sys

for _path in os.environ.get("INSTRUCTMOVE_BRIDGE_PATH", "").split(os.pathsep):
    if _path and _path not in sys.path:
        sys.path.append(_path)
