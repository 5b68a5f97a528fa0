"""A learned grounding model: which candidate (and receptacle) an instruction names, chosen
from what the policy's cameras show at the first step.

``crops`` cuts every object of a scene out of the 224 x 224 cameras (located by
segmentation), ``scenes`` renders and keeps training scenes and stored sets, ``text`` reads
instructions (words and character trigrams, learned from scratch), ``network`` scores the
options, ``training`` trains it resumably, ``judge`` measures its choices. Trained without
the instruction, the same network is the audit's pixel adversary; with it, it chooses for
``policies.GroundedPolicy``, the planner acting.
"""

from __future__ import annotations

from pathlib import Path

#: Training scenes per family and robot the shipped checkpoint learned from.
SCENES = 1000

#: The shipped checkpoint ``--policy grounded`` loads by default.
CHECKPOINT = Path(__file__).parent / "checkpoints" / "grounded.pt"
