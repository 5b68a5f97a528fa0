"""Joint-space plans (OMPL RRTConnect), straight-line Cartesian segments (IK along a line) and
their time parametrization into joint targets at the control frequency (``pd_joint_pos``)."""

from __future__ import annotations

import math

import numpy as np
import sapien
from ompl import base as ob
from ompl import geometric as og
from ompl import util as ou

from instructmove_ms.agents.hardware import JointLimits

from .collision import CollisionWorld
from .kinematics import ArmKinematics

ou.setLogLevel(ou.LOG_WARN)
#: OMPL seeds every sampler from one process-wide seed generator; ``plan_joint_path`` resets
#: it to this seed first, so that a plan depends only on its problem, not on the plans
#: before it.
OMPL_SEED = 1
#: Collision checks an RRTConnect attempt may spend (about a second here): a budget of work,
#: not of time, so that a loaded machine plans exactly what an idle one does.
CHECK_BUDGET = 5000


def densify(path: np.ndarray, max_step: float) -> np.ndarray:
    """Insert points so that no joint moves more than ``max_step`` between two rows."""
    out = [path[0]]
    for a, b in zip(path[:-1], path[1:], strict=True):
        n = max(1, math.ceil(float(np.abs(b - a).max()) / max_step))
        out.extend(a + (b - a) * k / n for k in range(1, n + 1))
    return np.asarray(out)


def path_is_free(world: CollisionWorld, path: np.ndarray, max_step: float = 0.01) -> bool:
    """Every state of ``path``, densified to ``max_step`` rad, is collision-free."""
    return not any(world.in_collision(q) for q in densify(path, max_step))


def _reseed() -> None:
    """Reset OMPL's seed generator to ``OMPL_SEED`` (quietly: OMPL warns that sampling has
    already started, which is the point)."""
    ou.setLogLevel(ou.LOG_NONE)
    ou.RNG.setSeed(OMPL_SEED)
    ou.setLogLevel(ou.LOG_WARN)


def stop_after(counter: list[int], checks: int) -> ob.PlannerTerminationCondition:
    """An OMPL termination condition: true once ``counter[0]`` reaches ``checks``."""
    return ob.PlannerTerminationCondition(lambda: counter[0] >= checks)


def plan_joint_path(
    world: CollisionWorld,
    start: np.ndarray,
    goal: np.ndarray,
    checks: int = CHECK_BUDGET,
    attempts: int = 2,
    max_step: float = 0.02,
) -> np.ndarray | None:
    """A collision-free joint path (rows: configurations, at most ``max_step`` rad apart per
    joint) from ``start`` to ``goal``, or None. Tries the straight line first, then RRTConnect
    (``attempts`` times, each ending after ``checks`` collision checks) with path
    simplification; every returned state passes ``world.in_collision``. The same problem
    gives the same path, whatever was planned before."""
    start, goal = np.asarray(start, dtype=float), np.asarray(goal, dtype=float)
    if world.in_collision(start) or world.in_collision(goal):
        return None
    line = densify(np.stack([start, goal]), max_step)
    if path_is_free(world, line, max_step):
        return line
    _reseed()
    kin, n = world.kin, len(start)
    space = ob.RealVectorStateSpace(n)
    bounds = ob.RealVectorBounds(n)
    for i in range(n):
        bounds.setLow(i, float(kin.lower[i]))
        bounds.setHigh(i, float(kin.upper[i]))
    space.setBounds(bounds)
    setup = og.SimpleSetup(space)
    done = [0]

    def valid(state) -> bool:
        done[0] += 1
        return not world.in_collision(np.array([state[i] for i in range(n)]))

    setup.setStateValidityChecker(valid)
    info = setup.getSpaceInformation()
    info.setStateValidityCheckingResolution(0.005)
    setup.setPlanner(og.RRTConnect(info))
    a, b = space.allocState(), space.allocState()
    for i in range(n):
        a[i], b[i] = float(start[i]), float(goal[i])
    setup.setStartAndGoalStates(a, b)
    for _ in range(attempts):
        setup.clear()
        done[0] = 0
        if not setup.solve(stop_after(done, checks)) or not setup.haveExactSolutionPath():
            continue
        done[0] = 0
        setup.simplifySolution(stop_after(done, checks))
        path = setup.getSolutionPath()
        rows = np.array(
            [[path.getState(k)[i] for i in range(n)] for k in range(path.getStateCount())]
        )
        rows = densify(rows, max_step)
        if path_is_free(world, rows, max_step / 2):
            return rows
    return None


def _slerp(q0: np.ndarray, q1: np.ndarray, t: float) -> np.ndarray:
    d = float(np.dot(q0, q1))
    if d < 0.0:
        q1, d = -q1, -d
    if d > 0.9995:
        q = q0 + t * (q1 - q0)
        return q / np.linalg.norm(q)
    theta = math.acos(d)
    return (math.sin((1 - t) * theta) * q0 + math.sin(t * theta) * q1) / math.sin(theta)


def cartesian_path(
    kin: ArmKinematics,
    start: np.ndarray,
    goal: sapien.Pose,
    world: CollisionWorld | None = None,
    step: float = 0.005,
    max_joint_step: float = 0.1,
    partial: bool = False,
) -> np.ndarray | None:
    """Joint configurations that move the end effector from its pose at ``start`` along a
    straight line (orientation slerped) to ``goal``, ``step`` metres apart; None where IK
    fails, a joint jumps more than ``max_joint_step`` rad, or ``world`` reports a collision
    (with ``partial``, the configurations up to there instead)."""
    begin = kin.fk(start)
    p0, p1 = np.asarray(begin.p, dtype=float), np.asarray(goal.p, dtype=float)
    r0, r1 = np.asarray(begin.q, dtype=float), np.asarray(goal.q, dtype=float)
    n = max(1, math.ceil(float(np.linalg.norm(p1 - p0)) / step))
    rows = [np.asarray(start, dtype=float)]
    for k in range(1, n + 1):
        t = k / n
        pose = sapien.Pose(p0 + t * (p1 - p0), _slerp(r0, r1, t))
        q = kin.ik(pose, seeds=[rows[-1]], num_random=0)
        if (
            q is None
            or float(np.abs(q - rows[-1]).max()) > max_joint_step
            or (world is not None and world.in_collision(q))
        ):
            return np.asarray(rows) if partial else None
        rows.append(q)
    return np.asarray(rows)


def _runs(path: np.ndarray, corner: float) -> list[np.ndarray]:
    """Split a polyline where its direction turns by more than ``corner`` radians."""
    keep = [0] + [k for k in range(1, len(path)) if np.abs(path[k] - path[k - 1]).max() > 1e-9]
    path = path[keep]
    runs, begin = [], 0
    for k in range(1, len(path) - 1):
        u, v = path[k] - path[k - 1], path[k + 1] - path[k]
        cos = float(u @ v) / (np.linalg.norm(u) * np.linalg.norm(v))
        if cos < math.cos(corner):
            runs.append(path[begin : k + 1])
            begin = k
    runs.append(path[begin:])
    return [r for r in runs if len(r) > 1]


def time_parametrize(
    path: np.ndarray, limits: JointLimits, dt: float = 1 / 30, corner: float = 0.2
) -> np.ndarray:
    """Joint targets every ``dt`` seconds following ``path`` (its first row excluded, its last
    row included). Each nearly straight run (split where the path turns by more than
    ``corner`` rad) gets a rest-to-rest trapezoidal profile within ``limits``."""
    out = []
    for run in _runs(np.asarray(path, dtype=float), corner):
        # s: time along the run at full speed; |dq_j/ds| <= v_j keeps every joint in bounds.
        ds = np.abs(np.diff(run, axis=0) / limits.velocity).max(axis=1)
        s = np.concatenate([[0.0], np.cumsum(ds)])
        total, acc = float(s[-1]), float(np.min(limits.acceleration / limits.velocity))
        if total < 1.0 / acc:  # triangular: never reaches full speed
            t_acc = math.sqrt(total / acc)
            peak, duration = acc * t_acc, 2 * t_acc
        else:
            t_acc, peak = 1.0 / acc, 1.0
            duration = total + t_acc
        for t in np.append(np.arange(1, math.ceil(duration / dt)) * dt, duration):
            if t < t_acc:
                at = 0.5 * acc * t * t
            elif t > duration - t_acc:
                at = total - 0.5 * acc * (duration - t) ** 2
            else:
                at = 0.5 * peak * t_acc + peak * (t - t_acc)
            at = min(max(at, 0.0), total)
            out.append([np.interp(at, s, run[:, j]) for j in range(run.shape[1])])
    return np.asarray(out).reshape(-1, path.shape[1])
