"""One read per step: the scene reader's poses and velocities equal ManiSkill's per-body
reads, ``touching`` agrees with the full contact list through a grasp (and answers from the
bounding boxes when a finger is far), and what a step reported stays as it was."""

from __future__ import annotations

import numpy as np
import pytest
import torch
from test_physics import _spec

from conftest import make_env
from instructmove_ms.agents.contacts import ContactForces
from scripted import CLOSED, OPEN, hold
from scripted import servo as move_to


@pytest.mark.parametrize("robot", ["franka", "piperx"])
def test_one_read_equals_maniskill_reads(robot):
    env = make_env(robot_uids=robot)
    env.reset(seed=3)
    rng = np.random.default_rng(0)
    u = env.unwrapped
    for _ in range(15):  # the arm moves and may knock objects: poses and velocities change
        env.step(torch.from_numpy(rng.uniform(-1, 1, env.action_space.shape).astype(np.float32)))
    u.objects[1].set_linear_velocity(torch.tensor([[0.0, 0.0, 1.0]]))  # tossed up
    env.step(torch.from_numpy(rng.uniform(-1, 1, env.action_space.shape).astype(np.float32)))
    now = u._reader.measure()
    objects = torch.stack([o.pose.raw_pose for o in u.objects], dim=1)
    tcps = torch.stack([link.pose.raw_pose for link in u.agent.tcp_links], dim=1)
    velocities = torch.stack([o.linear_velocity for o in u.objects], dim=1)
    assert now.objects.shape == (1, len(u.objects), 7)
    assert now.tcp.shape == (1, len(u.agent.tcp_links), 7)
    env.close()
    assert torch.equal(now.objects, objects)
    assert torch.equal(now.tcp, tcps)
    assert torch.equal(now.velocity, velocities)
    assert velocities[0, 1, 2] > 0.3, "the tossed object still rises"


def _touching_pairs(u) -> tuple[set, set]:
    """(finger, object) index pairs that the full contact list joins, and those that
    ``touching`` says may touch."""
    fingers = [link for pair in u.agent.finger_pairs for link, _ in pair]
    listed = {
        frozenset(body.entity for body in contact.bodies) for contact in u.scene.px.get_contacts()
    }
    joined, answered = set(), set()
    for i, finger in enumerate(fingers):
        for k, obj in enumerate(u.objects):
            forces = ContactForces(u.scene, fingers)
            if frozenset((finger._bodies[0].entity, obj._bodies[0].entity)) in listed:
                joined.add((i, k))
            if forces.touching(finger, obj):
                answered.add((i, k))
            elif forces._pairs is None:
                answered.add(("boxes apart", k))
    return joined, answered


def test_touching_agrees_with_the_contact_list_through_a_grasp():
    env = make_env(control_mode="pd_ee_delta_pose")
    env.reset(options={"episode": _spec(target=0), "verify": False})
    u = env.unwrapped
    hold(env, OPEN, 10)
    joined, answered = _touching_pairs(u)
    assert not joined and {k for _, k in answered} == set(range(len(u.objects)))
    assert all(i == "boxes apart" for i, _ in answered), "far fingers: no list is read"
    can = u.objects[0].pose.p[0].numpy()
    height = u.catalog[u.episode.objects[0].uuid].height
    move_to(env, can + [0, 0, height - 0.035], OPEN, steps=80)
    hold(env, CLOSED, 15)
    move_to(env, can + [0, 0, 0.2], CLOSED, steps=80)
    joined, answered = _touching_pairs(u)
    env.close()
    assert {(0, 0), (1, 0)} <= joined, "both fingers hold the can"
    assert joined == {pair for pair in answered if pair[0] != "boxes apart"}


def test_a_step_report_stays_as_it_was():
    """The latched flags are new tensors each step: an info kept from an early step is not
    rewritten by later steps or by a reset."""
    env = make_env(control_mode="pd_ee_delta_pose")
    env.reset(options={"episode": _spec(target=0), "verify": False})
    u = env.unwrapped
    hold(env, OPEN, 5)
    can = u.objects[0].pose.p[0].numpy()
    height = u.catalog[u.episode.objects[0].uuid].height
    early = move_to(env, can + [0, 0, 0.2], OPEN)
    ours = [k for k in early if k != "elapsed_steps"]  # ManiSkill's counter is one live tensor
    kept = {k: early[k].clone() for k in ours}
    late = move_to(env, can + [0, 0, height - 0.035], OPEN, steps=80)
    assert bool(late["reach"]) and int(late["reached_object"]) == 0
    env.reset(options={"episode": _spec(target=0), "verify": False})
    env.close()
    for key, value in kept.items():
        assert torch.equal(early[key], value), key
