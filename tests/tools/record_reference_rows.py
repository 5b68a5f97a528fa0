"""Record tests/data/reference_rows.json on this machine (whose CPU it then names), or with
``--ulps N`` measure instead how many rows of a slice of ``--episodes`` per family change when
every object is nudged by N float32 ULPs at reset (what ``ALLOWED_ROWS`` rests on):

    python tests/tools/record_reference_rows.py
    python tests/tools/record_reference_rows.py --ulps 1 --episodes 10
"""

import argparse
import json
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from test_reference_rows import EPISODES, PATH, differing, nudged, slice_rows  # noqa: E402

from instructmove_ms.files import write_text  # noqa: E402
from instructmove_ms.floats import cpu_model, describe  # noqa: E402

parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
parser.add_argument("--ulps", type=int, default=0, help="measure with objects nudged instead")
parser.add_argument("--episodes", type=int, default=EPISODES)
args = parser.parse_args()
robots = ("franka", "piperx")
if args.ulps:
    total = changed = 0
    for robot in robots:
        stored = slice_rows(robot, args.episodes)
        with nudged(args.ulps):
            moved = slice_rows(robot, args.episodes)
        rows = differing(stored, moved)
        total += sum(len(run) for run in stored.values())
        changed += len(rows)
        print(f"{robot}: {len(rows)} rows changed {rows}", flush=True)
    print(f"{changed} of {total} rows changed with every object nudged by {args.ulps} ULP")
else:
    if args.episodes != EPISODES:
        sys.exit(f"the test's slice is {EPISODES} episodes per family")
    data = {"recorded_on": {"cpu": cpu_model(), "set_up": describe()}, "episodes": EPISODES}
    data.update({robot: slice_rows(robot) for robot in robots})
    write_text(PATH, json.dumps(data, indent=1) + "\n")
    print(f"recorded on {data['recorded_on']['set_up']}")
