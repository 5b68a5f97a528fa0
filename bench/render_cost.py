"""Rendering cost per camera: our default cameras against ManiSkill's PickCube-v1 camera at
the same resolution, in the same run.

For each env (PickCategory with either robot, PickCube-v1 as the baseline) with rgb
observations and every sensor camera set to ``--width`` x ``--height`` (PickCube-v1's own
128 x 128 by default), it times, after a warm-up, one render update of the scene plus each
camera's capture and rgb read-out (ManiSkill's own sensor path), and prints milliseconds per
camera and the ratio to PickCube-v1's. Medians of ``--repeats`` interleaved rounds of
``--frames``.
"""

from __future__ import annotations

import argparse
import statistics
import time

import gymnasium as gym

import instructmove_ms  # noqa: F401

ENVS = (("PickCube-v1", None), ("PickCategory-InstructMove", "franka"))
ENVS += (("PickCategory-InstructMove", "piperx"),)
WARMUP = 5


def per_camera_ms(env_id: str, robot: str | None, size: tuple[int, int], frames: int) -> dict:
    """Milliseconds per frame of each camera (its share of the scene's render update
    included) and the update itself."""
    extra = {"robot_uids": robot} if robot else {}
    env = gym.make(
        env_id,
        obs_mode="rgb",
        sensor_configs={"width": size[0], "height": size[1]},
        render_backend="cpu",
        **extra,
    )
    env.reset(seed=0)
    scene = env.unwrapped.scene
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


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--width", type=int, default=128)
    parser.add_argument("--height", type=int, default=128)
    parser.add_argument("--frames", type=int, default=20)
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    size = (args.width, args.height)
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
