"""Contact forces between the robot and the rest of the scene: the physics check of a demo
(a planned motion must not press on the table or on objects other than the one it grasps)."""

from __future__ import annotations

from collections.abc import Iterable

import numpy as np

from instructmove_ms.episode import actor_name

#: Newtons above which a robot contact with the table or a distractor counts as a collision.
FORCE_LIMIT = 5.0


def robot_contacts(env, ignore: Iterable[str] = ()) -> dict[tuple[str, str], float]:
    """Contact force (N) between each robot link and each other body it touches at the last
    physics step of sub-scene 0, keyed (link name, body name). Bodies are named as the env
    names them (``table``, ``object_k``); those in ``ignore`` are left out."""
    u = env.unwrapped
    links = {link._objs[0].entity: link.name for link in u.agent.robot.get_links()}
    bodies = {actor._objs[0]: name for name, actor in u.scene.actors.items()}
    bodies.update({actor._objs[0]: actor.name for actor in u.objects})
    skip = set(ignore)
    impulses: dict[tuple[str, str], np.ndarray] = {}
    for contact in u.scene.get_contacts():
        a, b = (body.entity for body in contact.bodies)
        if (a in links) == (b in links):
            continue
        link, other, sign = (a, b, 1.0) if a in links else (b, a, -1.0)
        name = bodies.get(other, other.name)
        if name in skip:
            continue
        key = (links[link], name)
        impulse = sign * np.sum([point.impulse for point in contact.points], axis=0)
        impulses[key] = impulses.get(key, np.zeros(3)) + impulse
    dt = u.scene.px.timestep
    return {key: float(np.linalg.norm(v)) / dt for key, v in impulses.items()}


def collisions(env, limit: float = FORCE_LIMIT) -> dict[tuple[str, str], float]:
    """Robot contacts above ``limit`` N with anything but the episode's target."""
    target = actor_name(env.unwrapped.episode.target)
    return {k: f for k, f in robot_contacts(env, ignore=[target]).items() if f > limit}
