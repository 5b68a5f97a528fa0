"""Quality checks of generated instances: geometry, size priors and physical stability."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import sapien.physx as physx

from .affordances import grasp_affordances
from .catalog import Instance
from .generators import GENERATORS
from .sim import TIMESTEP, spawn, table_scene

SETTLE_SECONDS = 1.5
GRIPPER_OPENING = 0.08  # the Franka's; the PiperX opens to 0.1 m
MAX_DRIFT = 0.01  # metres in xy
MAX_TILT = math.radians(10.0)  # resting on a rounded end tilts a little


@dataclass
class CheckResult:
    uuid: str
    category: str
    failures: list[str] = field(default_factory=list)

    @property
    def ok(self) -> bool:
        return not self.failures


def check_geometry(inst: Instance) -> list[str]:
    """Collision parts exist, the mass is positive and the size fits the category prior."""
    failures = []
    if not any(not p.visual_only for p in inst.parts):
        failures.append("no collision part")
    if inst.mass <= 0:
        failures.append(f"mass {inst.mass}")
    prior = GENERATORS.get(inst.category)  # imported categories may have no prior
    largest = max(inst.dims)
    if prior and not prior.size[0] <= largest <= prior.size[1]:
        failures.append(f"largest dimension {largest:.3f} m outside prior {list(prior.size)}")
    if inst.is_graspable and not grasp_affordances(inst, GRIPPER_OPENING):
        failures.append(f"graspable but no top-down grasp for a {GRIPPER_OPENING} m gripper")
    if inst.is_container:
        region = inst.interior
        if region is None or min(region.half) <= 0 or region.height <= 0:
            failures.append("container without a valid interior")
    return failures


def _tilt(q: np.ndarray) -> float:
    """Angle between the object's z axis and the world's, from a wxyz quaternion."""
    w, x, y, _ = q
    return math.acos(float(np.clip(1 - 2 * (x * x + y * y), -1.0, 1.0)))


def check_settles(instances: list[Instance], seconds: float = SETTLE_SECONDS) -> dict[str, str]:
    """Drop each instance 2 mm onto a table; report those that drift, tip or keep moving."""
    scene = table_scene()
    entities = []
    for k, inst in enumerate(instances):  # far apart in one scene, so one simulation serves all
        xy = ((k % 20) * 0.6, (k // 20) * 0.6)
        entities.append((inst, xy, spawn(scene, inst, xy=xy)))
    for _ in range(int(seconds / TIMESTEP)):
        scene.step()
    failures = {}
    for inst, xy, entity in entities:
        pose = entity.pose
        body = entity.find_component_by_type(physx.PhysxRigidDynamicComponent)
        drift = float(np.linalg.norm(np.asarray(pose.p[:2]) - np.asarray(xy)))
        tilt = _tilt(np.asarray(pose.q))
        speed = float(np.linalg.norm(body.linear_velocity))
        if drift > MAX_DRIFT:
            failures[inst.uuid] = f"drifted {drift * 100:.1f} cm"
        elif tilt > MAX_TILT:
            failures[inst.uuid] = f"tipped {math.degrees(tilt):.1f} deg"
        elif speed > 0.01:
            failures[inst.uuid] = f"still moving at {speed:.3f} m/s"
    return failures


def check_instances(instances: list[Instance]) -> list[CheckResult]:
    results = [CheckResult(i.uuid, i.category, check_geometry(i)) for i in instances]
    unstable = check_settles(instances)
    for result in results:
        if result.uuid in unstable:
            result.failures.append(unstable[result.uuid])
    return results
