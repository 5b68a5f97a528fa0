"""GR00T's view of our LeRobot datasets: ``meta/modality.json`` and a modality config for
Isaac-GR00T's fine-tuning script.

``modality.json`` names slices of ``observation.state`` and ``action`` after the robot's
policy interface (``arm`` and ``gripper``, or ``left_arm`` ... ``right_gripper`` on the
PiperX; ``PolicyInterface.parts``), maps each camera's video key to its feature, and the
instruction to the ``annotation.human.task_description`` column (task indices into the task
table). The modality config (``groot_modality_config.py``) declares the same keys for a new
embodiment: the current frame of every camera and state part, an action chunk of
``ACTION_HORIZON`` steps, absolute joint targets.
"""

from __future__ import annotations

from pathlib import Path

from instructmove_ms.files import write_json, write_text
from instructmove_ms.obs_formats import GROOT_LANGUAGE

from .lerobot_formats import IMAGE

MODALITY = "meta/modality.json"
CONFIG = "groot_modality_config.py"
ACTION_HORIZON = 16  # GR00T N1.6's default action horizon


def modality(record: dict) -> dict:
    """``meta/modality.json`` of a dataset whose first episode's record is ``record``."""
    parts = {name: {"start": start, "end": end} for name, (start, end) in record["parts"].items()}
    return {
        "state": parts,
        "action": parts,
        "video": {cam: {"original_key": IMAGE.format(cam)} for cam in record["cameras"]},
        "annotation": {GROOT_LANGUAGE.removeprefix("annotation."): {}},
    }


def write_modality(out: Path, record: dict, settings) -> None:
    """``meta/modality.json`` and the modality config file of the dataset at ``out``."""
    write_json(out / MODALITY, modality(record), indent=4)
    write_text(out / CONFIG, config_file(record, settings.repo_id))


def config_file(record: dict, repo_id: str) -> str:
    """A modality config for Isaac-GR00T N1.6/N1.7's ``--modality-config-path``."""
    return CONFIG_TEMPLATE.format(
        repo_id=repo_id,
        cameras=list(record["cameras"]),
        parts=list(record["parts"]),
        language=GROOT_LANGUAGE,
        horizon=ACTION_HORIZON,
    )


CONFIG_TEMPLATE = '''\
"""GR00T modality config for the InstructMove dataset {repo_id} (written by
`instructmove export lerobot`). Pass it to Isaac-GR00T's fine-tuning script with
--modality-config-path and --embodiment-tag NEW_EMBODIMENT; the dataset's
meta/modality.json names the same keys."""

from gr00t.configs.data.embodiment_configs import register_modality_config
from gr00t.data.embodiment_tags import EmbodimentTag
from gr00t.data.types import (
    ActionConfig,
    ActionFormat,
    ActionRepresentation,
    ActionType,
    ModalityConfig,
)

CAMERAS = {cameras!r}
PARTS = {parts!r}

instructmove_config = {{
    "video": ModalityConfig(delta_indices=[0], modality_keys=CAMERAS),
    "state": ModalityConfig(delta_indices=[0], modality_keys=PARTS),
    "action": ModalityConfig(
        delta_indices=list(range({horizon})),
        modality_keys=PARTS,
        action_configs=[
            ActionConfig(
                rep=ActionRepresentation.ABSOLUTE,
                type=ActionType.NON_EEF,
                format=ActionFormat.DEFAULT,
            )
            for _ in PARTS
        ],
    ),
    "language": ModalityConfig(delta_indices=[0], modality_keys=[{language!r}]),
}}

register_modality_config(instructmove_config, embodiment_tag=EmbodimentTag.NEW_EMBODIMENT)
'''
