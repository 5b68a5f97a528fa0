"""Rendering cost per camera: our default cameras against ManiSkill's PickCube-v1 camera at
the same resolution, in the same run.

For each env (PickCategory with either robot, PickCube-v1 as the baseline) with rgb
observations and every sensor camera set to ``--width`` x ``--height`` (PickCube-v1's own
128 x 128 by default), it times, after a warm-up, one render update of the scene plus each
camera's capture and rgb read-out (ManiSkill's own sensor path), and prints milliseconds per
camera and the ratio to PickCube-v1's. Medians of ``--repeats`` interleaved rounds of
``--frames``.

``--profile`` says where a render's time goes instead, per robot and camera at ``--width`` x
``--height``: the whole scene, then with the robot's render bodies removed (disabled), the
episode's objects removed, the table and floor removed, without shadows, and (the Franka) with
ManiSkill's full visual meshes; then the three cameras together at 128, 224 and 320 pixels a
side. Every figure is a ratio to the whole scene's time in the same round.

``--robot-share`` times only the whole scene against the same scene with the robot's render
bodies removed, per robot, over ``--repeats`` paired rounds in alternating order (more rounds
than the profile's, for the one ratio the Franka's render target is stated in: whole /
without robot).
"""

from __future__ import annotations

import argparse
import statistics
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager

import gymnasium as gym
import sapien
from mani_skill.agents.robots.panda.panda import Panda

import instructmove_ms  # noqa: F401
from instructmove_ms.agents.franka import FrankaInstructMove

ENVS = (("PickCube-v1", None), ("PickCategory-InstructMove", "franka"))
ENVS += (("PickCategory-InstructMove", "piperx"),)
WARMUP = 5


def _entities(objs) -> list:
    return [o.entity if hasattr(o, "entity") else o for x in objs for o in x._objs]


#: What ``--profile`` hides, by name: the entities of an env (unwrapped) that make each part.
PARTS = {
    "robot": lambda u: _entities(u.agent.robot.get_links()),
    "objects": lambda u: _entities(u.objects),
    "table and floor": lambda u: [
        o
        for name, a in u.scene.actors.items()
        if name not in {x.name for x in u.objects}
        for o in _entities([a])
    ],
}


def per_camera_ms(
    env_id: str,
    robot: str | None,
    size: tuple[int, int],
    frames: int,
    hide: str | None = None,
    **kwargs,
) -> dict:
    """Milliseconds per frame of each camera (its share of the scene's render update
    included), with the render bodies of ``hide`` (a key of ``PARTS``) removed."""
    extra = {"robot_uids": robot} if robot else {}
    env = gym.make(
        env_id,
        obs_mode="rgb",
        sensor_configs={"width": size[0], "height": size[1]},
        render_backend="cpu",
        **extra,
        **kwargs,
    )
    env.reset(seed=0)
    scene = env.unwrapped.scene
    for entity in PARTS[hide](env.unwrapped) if hide else ():
        body = entity.find_component_by_type(sapien.render.RenderBodyComponent)
        if body is not None:
            body.disable()
    cameras = dict(scene.sensors)
    times = {name: [] for name in cameras} | {"update": []}
    for k in range(WARMUP + frames):
        start = time.perf_counter()
        scene.update_render(update_sensors=True, update_human_render_cameras=False)
        update = time.perf_counter() - start
        for name, camera in cameras.items():
            start = time.perf_counter()
            camera.capture()
            camera.get_obs(rgb=True, depth=False, segmentation=False, position=False)
            if k >= WARMUP:
                times[name].append(time.perf_counter() - start)
        if k >= WARMUP:
            times["update"].append(update)
    env.close()
    share = statistics.mean(times.pop("update")) / len(cameras)
    return {name: (statistics.mean(t) + share) * 1000 for name, t in times.items()}


@contextmanager
def full_franka_meshes() -> Iterator[None]:
    """Franka envs made inside load ManiSkill's own (full) visual meshes."""
    light, FrankaInstructMove.urdf_path = FrankaInstructMove.urdf_path, Panda.urdf_path
    try:
        yield
    finally:
        FrankaInstructMove.urdf_path = light


def _variants(robot: str, size: tuple[int, int], frames: int) -> dict[str, Callable[[], dict]]:
    """What ``--profile`` times for ``robot``, by name: per-camera milliseconds."""

    def timed(size=size, **variant) -> Callable[[], dict]:
        return lambda: per_camera_ms("PickCategory-InstructMove", robot, size, frames, **variant)

    out = {"whole scene": timed()}
    out |= {f"{part} removed": timed(hide=part) for part in PARTS}
    out["no shadows"] = timed(enable_shadow=False)
    if robot == "franka":
        whole = out["whole scene"]

        def full() -> dict:
            with full_franka_meshes():
                return whole()

        out["full visual meshes"] = full
    out |= {f"{side} x {side}": timed(size=(side, side)) for side in (128, 224, 320)}
    return out


def profile(size: tuple[int, int], frames: int, repeats: int) -> None:
    """Where a render's time goes, per robot (see the module docstring): medians of
    ``repeats`` interleaved rounds, each variant as a ratio to the whole scene."""
    for robot in ("franka", "piperx"):
        variants = _variants(robot, size, frames)
        rounds: dict[str, list[dict]] = {name: [] for name in variants}
        for _ in range(repeats):
            for name, measure in variants.items():
                rounds[name].append(measure())
        ms = {
            name: {c: statistics.median(r[c] for r in runs) for c in runs[0]}
            for name, runs in rounds.items()
        }
        whole = ms.pop("whole scene")
        total = sum(whole.values())
        print(f"\n{robot} at {size[0]} x {size[1]}, rgb (ratios to the whole scene's time)")
        print("| variant | " + " | ".join(whole) + " | all cameras |")
        print("|---|" + "---|" * (len(whole) + 1))
        cells = [f"{v:.1f} ms" for v in whole.values()]
        print("| whole scene | " + " | ".join(cells) + f" | {total:.1f} ms |")
        for name, cameras in ms.items():
            cells = [f"{cameras[c] / whole[c]:.2f}x" for c in whole]
            print(f"| {name} | " + " | ".join(cells) + f" | {sum(cameras.values()) / total:.2f}x |")


def robot_share(size: tuple[int, int], frames: int, repeats: int) -> None:
    """Per robot: the three cameras' time with and without the robot's render bodies, and
    their ratio, from ``repeats`` rounds of the two measured back to back (in alternating
    order, so a drift between rounds or a second-place penalty cancels): medians, and the
    middle half of the rounds' ratios."""
    print(f"robot share at {size[0]} x {size[1]}, rgb, {repeats} paired rounds")
    for robot in ("franka", "piperx"):
        whole, bare, ratios = [], [], []
        for k in range(repeats):
            order = (None, "robot") if k % 2 == 0 else ("robot", None)
            ms = {
                hide: sum(
                    per_camera_ms("PickCategory-InstructMove", robot, size, frames, hide).values()
                )
                for hide in order
            }
            whole.append(ms[None])
            bare.append(ms["robot"])
            ratios.append(ms[None] / ms["robot"])
        q1, median, q3 = statistics.quantiles(ratios, n=4)
        print(
            f"{robot:7s} whole {statistics.median(whole):5.1f} ms   without the robot "
            f"{statistics.median(bare):5.1f} ms   {median:.2f}x (middle half {q1:.2f}-{q3:.2f}x)"
        )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--width", type=int, default=128)
    parser.add_argument("--height", type=int, default=128)
    parser.add_argument("--frames", type=int, default=20)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--profile", action="store_true", help="where a render's time goes")
    parser.add_argument(
        "--robot-share", action="store_true", help="whole scene vs without the robot"
    )
    args = parser.parse_args()
    size = (args.width, args.height)
    if args.profile:
        profile(size, args.frames, args.repeats)
        return
    if args.robot_share:
        robot_share(size, args.frames, args.repeats)
        return
    rounds: dict[str, list[dict]] = {robot or env_id: [] for env_id, robot in ENVS}
    for _ in range(args.repeats):  # interleaved: the renderer's first start-up is one round's
        for env_id, robot in ENVS:
            rounds[robot or env_id].append(per_camera_ms(env_id, robot, size, args.frames))
    results = {
        env: {name: statistics.median(r[name] for r in runs) for name in runs[0]}
        for env, runs in rounds.items()
    }
    (base,) = results["PickCube-v1"].values()
    print(f"per-camera render time at {size[0]} x {size[1]} (rgb), vs PickCube-v1's camera")
    for env, cameras in results.items():
        for name, ms in cameras.items():
            print(f"{env:12s} {name:18s} {ms:6.2f} ms   {ms / base:.2f}x")


if __name__ == "__main__":
    main()
