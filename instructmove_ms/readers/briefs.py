"""What each reader is told, word for word (``OUT/reader/BRIEF.txt``). A reader sees only
this brief and the material beside it: never the code, the names, the key, earlier
sheets or earlier answers."""

from __future__ import annotations

from . import POLICY_RESOLUTION

_ANSWER = (
    "Write one line per number, in the form `N: answer`, in a plain text file. Answer "
    "every number; if you are unsure, still give your best guess."
)

BRIEFS = {
    "close_ups": f"""\
Each numbered picture (close_ups_*.png) shows one everyday object on a plain surface.
For each number, say what the object is, in the words you would use to name it to a
friend (for example `7: teapot`). Give your first guess first; you may add other guesses
after a semicolon (`7: teapot; kettle`), but only the first one counts.
{_ANSWER}
""",
    "in_scene": f"""\
Each numbered picture (in_scene_*.png) is what a robot's camera sees of a table, at
{{side}} x {{side}} pixels. One object in each picture has a thin magenta box around it.
For each number, say what that object is, in the words you would use to name it to a
friend (for example `7: teapot`). Give your first guess first; you may add other guesses
after a semicolon, but only the first one counts.
{_ANSWER}
""",
    "instructions": f"""\
instructions.txt holds numbered instructions that a person might say to a household robot
working at a table. For each, judge the wording as a native English speaker:
  natural   - something a person would say to the robot, as it is
  odd       - clear, but not how a person would put it
  unnatural - wrong, garbled or hard to understand
  ambiguous - could mean two different objects or two different actions
Answer `N: natural`, or `N: odd - why` (likewise for unnatural and ambiguous).
{_ANSWER}
""",
    "episodes": f"""\
Each episode is a picture (episode_N.png) of what a robot's cameras see at one moment,
side by side (camera 1, camera 2, ...), each ruled into a grid: columns A-H from left to
right, rows 1-8 from top to bottom, marked in the margin. episodes.txt holds each
episode's instruction to the robot. Find the object the instruction asks for and answer
with one camera and the grid cell that holds most of it: `N: 2 C4`. Where the instruction
also says where to put the object, add the place after a slash: `N: 2 C4 / 1 F6`.
{_ANSWER}
""",
}


def brief(kind: str, side: int = POLICY_RESOLUTION) -> str:
    """What a reader of ``kind`` is told; in-scene pictures are ``side`` pixels square."""
    return BRIEFS[kind].replace("{side}", str(side))
