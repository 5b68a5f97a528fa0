"""Record cases of tests/data/step_reference.json again, with the scoring as it is now
(only when a change of the scene or the physics moves them, never to make a scoring change
pass):

    python tests/tools/record_step_reference.py "PickSpatial-InstructMove/piperx" [...]
"""

import json
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from test_step_reference import REFERENCE, replayed  # noqa: E402

from instructmove_ms.files import write_text  # noqa: E402

path = Path(__file__).resolve().parents[1] / "data" / "step_reference.json"
data = dict(REFERENCE)
for case in sys.argv[1:]:
    with tempfile.TemporaryDirectory() as tmp:
        data[case] = replayed(case, Path(tmp), REFERENCE[case]["steps"])
    print(f"{case}: seed {data[case]['seed']}, {len(data[case]['steps']['reward'])} steps")
write_text(path, json.dumps(data, separators=(",", ":")))
