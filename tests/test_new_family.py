"""A fifth family declared in this file alone: PickMaterial, a pick family whose cue is the
material ("the wooden spoon" among same-category objects of other materials). It runs
through composition, the verifier, an env reset, the planner oracle, scoring and the
metrics without any change to the package."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import gymnasium as gym
import numpy as np
import pytest
from mani_skill.utils.registration import register_env

from instructmove_ms.assets.catalog import Catalog, Instance
from instructmove_ms.episode import EpisodeSpec
from instructmove_ms.family import Cue, Members, TaskSpec
from instructmove_ms.language import attribute_word, names, noun
from instructmove_ms.metrics import aggregate, markdown_table, paper_cell, score_episode
from instructmove_ms.policies import OraclePolicy
from instructmove_ms.sampler import EACH_OTHER, Constraint, RoleError, RoleSpec, with_constraints
from instructmove_ms.tasks import PICK_STAGES, InstructMoveEnv
from instructmove_ms.tasks.pick_category import PICK_TEMPLATES
from instructmove_ms.verify import verify

ENV_ID = "PickMaterial-InstructMoveTest"


@dataclass(frozen=True)
class MaterialCue(Cue):
    """The goal is named by its material; the candidates share a category and have pairwise
    different materials, each with a word, so any of them can be named."""

    def draw(self, rng: np.random.Generator, roles: tuple[RoleSpec, ...]):
        extra = (
            Constraint("material", "differ", "target"),
            Constraint("material", "differ", EACH_OTHER),
        )
        return {"kind": "material"}, with_constraints(roles, "distractor", *extra)

    def admits(self, cue: dict, assigned: dict[str, list[Instance]]) -> None:
        for inst in assigned["target"] + assigned["distractor"]:
            if attribute_word(inst, "material") is None:
                raise RoleError(f"no word for the material of {inst.category}")

    def phrase(self, rng, cue: dict, members: Members, goal: int, split: str, sampler: int) -> str:
        inst = members[goal][0]
        return f"{attribute_word(inst, 'material')} {noun(rng, inst)}"

    def matches(self, spec: EpisodeSpec, catalog: Catalog, k: int) -> bool:
        inst = catalog[spec.objects[k].uuid]
        word = attribute_word(inst, "material")
        others = [catalog[spec.objects[c].uuid] for c in spec.candidates if c != k]
        return (
            names(inst, spec.instruction)
            and f" {word} " in f" {spec.instruction} "
            and all(o.material != inst.material for o in others)
        )


PICK_MATERIAL = TaskSpec(
    env_id=ENV_ID,
    family="pick_material",
    default_robot="franka",
    supported_robots=("franka", "piperx"),
    cue=MaterialCue(),
    stages=PICK_STAGES,
    roles=(
        RoleSpec("target", 1, pool="target"),
        RoleSpec(
            "distractor", 1, pool="any", constraints=(Constraint("category", "match", "target"),)
        ),
    ),
    count_limits={"distractor": (1, 2)},
    templates=PICK_TEMPLATES,
)


@register_env(ENV_ID, max_episode_steps=PICK_MATERIAL.max_episode_steps)
class PickMaterialEnv(InstructMoveEnv):
    """**Task Description:** pick up the object of the named material.

    **Randomizations:** category, instances, positions, yaw, template, robot joints.

    **Success Conditions:** ``reach`` then ``lift`` of the target, as every pick family.
    """

    task = PICK_MATERIAL


@pytest.fixture(scope="module")
def env():
    env = gym.make(ENV_ID, obs_mode="state", control_mode="pd_joint_pos", render_backend="none")
    yield env
    env.close()


def _verify(spec: EpisodeSpec, env) -> list[str]:
    return verify(spec, env.unwrapped.catalog, PICK_MATERIAL, env.unwrapped.agent.gripper.max_width)


def test_episodes_name_the_target_by_its_material_and_verify(env):
    catalog = env.unwrapped.catalog
    for seed in range(8):
        spec = env.unwrapped.sample_episode(seed)
        target = catalog[spec.target_object.uuid]
        assert spec.family == "pick_material" and spec.cue == {"kind": "material"}
        assert attribute_word(target, "material") in spec.instruction.split()
        materials = {catalog[spec.objects[k].uuid].material for k in spec.candidates}
        assert len(materials) == len(spec.candidates) == 2, "one material per candidate"
        assert _verify(spec, env) == [], (seed, spec.instruction)
        other = env.unwrapped.sample_episode(seed, "alternative_target")
        assert other.target != spec.target and _verify(other, env) == []


def test_the_verifier_refuses_the_wrong_material(env):
    catalog = env.unwrapped.catalog
    spec = env.unwrapped.sample_episode(0)
    wrong = next(k for k in spec.candidates if k != spec.target)
    word = attribute_word(catalog[spec.objects[wrong].uuid], "material")
    text = f"pick up the {word} {catalog[spec.target_object.uuid].nouns[0]}"
    problems = _verify(dataclasses.replace(spec, instruction=text), env)
    assert problems and "matches candidates" in problems[0]


def test_reset_oracle_scoring_and_metrics(env):
    """The env rebuilds each episode, the planner oracle picks its target up (the object
    rises in the hand), and the results score and aggregate in the pick format."""
    u = env.unwrapped
    results = []
    for seed in (0, 1):
        spec = u.sample_episode(seed)
        obs, _ = env.reset(options={"episode": spec})
        assert u.episode == spec and [a.name for a in u.objects] == ["object_0", "object_1"]
        target = u.objects[spec.target]
        z0 = float(target.pose.p[0, 2])
        policy = OraclePolicy()
        policy.bind(env)
        policy.reset(obs)
        for _ in range(PICK_MATERIAL.max_episode_steps):  # the plan, then holding still
            obs, _, _, _, info = env.step(policy.act(obs))
        assert float(target.pose.p[0, 2]) - z0 > 0.05, "the target rose"
        assert bool(u.agent.is_grasping(target)[0]), "in the hand"
        results.append(score_episode(spec, info, PICK_MATERIAL.stages, u.catalog))
    assert all(r.stages == {"reach": True, "lift": True} and r.success for r in results)
    (row,) = aggregate(results)
    assert row["family"] == "pick_material" and row["stages"] == ["reach", "lift"]
    assert paper_cell(row) == "1.00/1.00 (1.00)" and row["chance"] == 0.5
    assert "| pick_material | franka | train | normal | 2 | 1.00/1.00 (1.00) |" in (
        markdown_table([row])
    )
