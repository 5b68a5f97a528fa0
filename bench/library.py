"""Object library figures: build time, 7-object scene build time, memory.

Each figure is printed with a baseline measured in the same run: generating the library
against generating the same number of one-box objects, a scene of 7 library objects against a
scene of 7 boxes, and the memory of the loaded library against a bare interpreter with the
same imports.
"""

from __future__ import annotations

import argparse
import resource
import statistics
import time

import numpy as np

from instructmove_ms.assets import load_snapshot
from instructmove_ms.assets.catalog import generate_instance
from instructmove_ms.assets.design import Design
from instructmove_ms.assets.generators import GENERATORS
from instructmove_ms.assets.sim import spawn, table_scene


def rss_mb() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def one_box(seed: int) -> list:
    d = Design(np.random.default_rng(seed))
    d.box("body", (0.02, 0.02, 0.02), (0, 0, 0.02), "plastic", "red")
    return d.finish()


def timed(fn, repeats: int) -> float:
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        fn()
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--repeats", type=int, default=5)
    args = parser.parse_args()
    before = rss_mb()
    catalog = load_snapshot()
    n = len(catalog)
    cats = sorted(GENERATORS)
    per = n // len(cats)
    build = timed(lambda: [generate_instance(c, i) for c in cats for i in range(per)], 1)
    base = timed(lambda: [one_box(i) for i in range(len(cats) * per)], 1)
    print(
        f"library: {len(cats)} categories, {n} instances, built in {build:.2f} s "
        f"({build / n * 1e3:.2f} ms each; {build / base:.1f}x a one-box object)"
    )
    print(f"memory: {rss_mb() - before:.1f} MB for the loaded library (peak RSS {rss_mb():.0f} MB)")
    rng = np.random.default_rng(0)
    picks = [catalog.instances[int(k)] for k in rng.choice(n, size=7, replace=False)]
    cube = generate_instance("eraser", 0)

    scene = table_scene()

    def scene_of(instances) -> None:
        entities = [spawn(scene, inst, xy=(0.3 * k, 0.0)) for k, inst in enumerate(instances)]
        for entity in entities:
            scene.remove_entity(entity)

    ours = timed(lambda: scene_of(picks), args.repeats)
    boxes = timed(lambda: scene_of([cube] * 7), args.repeats)
    parts = sum(len(i.parts) for i in picks)
    print(
        f"7 objects built into a scene: {ours * 1e3:.1f} ms ({parts} parts) vs 7 two-part erasers "
        f"{boxes * 1e3:.1f} ms: ratio {ours / boxes:.2f}"
    )


if __name__ == "__main__":
    main()
