"""The deterministic scorer of readers' answers (docs/readers.md, "Scoring").

- Names (close-ups, in-scene): a category counts for a reader when the first guess names it
  (``names.names_category``); it is named when at least ``agreement`` readers named it
  (default: two thirds of them, rounded up).
- Instructions: each reader's judgements counted (natural, odd, unnatural, ambiguous); an
  instruction counts as natural when at least ``agreement`` readers said so.
- Episodes: found when the named camera's cell is held mostly by the target (and, for a
  place, the second cell by the destination).
"""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

from .names import names_category
from .pictures import COLUMNS, GRID

JUDGEMENTS = ("natural", "odd", "unnatural", "ambiguous")
LINE = re.compile(r"^\s*(\d+)\s*[:.)]\s*(.*)$")
CELL = re.compile(r"^\s*(\d+)\s*([A-Ha-h])\s*([1-8])\s*$")


def read_answers(path: Path, count: int) -> dict[int, str]:
    """``N: answer`` lines of ``path``; an error names a number outside 1..``count``."""
    answers = {}
    for line in Path(path).read_text().splitlines():
        match = LINE.match(line)
        if not match:
            continue
        n = int(match.group(1))
        if not 1 <= n <= count:
            raise ValueError(f"{path}: answer number {n} outside 1..{count}")
        answers.setdefault(n, match.group(2).strip())
    return answers


def default_agreement(readers: int) -> int:
    return max(1, math.ceil(2 * readers / 3))


def judgement(answer: str) -> str | None:
    """The judgement word an instruction answer starts with (None if none)."""
    word = re.split(r"[\s:\-,.]", answer.strip().lower(), maxsplit=1)[0]
    return word if word in JUDGEMENTS else None


def found(answer: str, item: dict) -> bool:
    """Whether an episode answer (``2 C4`` or ``2 C4 / 1 F6``) points at the target (and
    the destination, where the episode has one): a cell the object holds most of, or
    (where the key records it) the cell holding most of the object."""
    wanted = [item["target"]] + ([item["destination"]] if item["destination"] >= 0 else [])
    parts = answer.split("/")
    if len(parts) < len(wanted):
        return False
    for part, k in zip(parts, wanted, strict=False):
        match = CELL.match(part)
        if not match:
            return False
        camera = int(match.group(1)) - 1
        if not 0 <= camera < len(item["owners"]):
            return False
        row, col = int(match.group(3)) - 1, COLUMNS.index(match.group(2).upper())
        most = item.get("most", [{}] * len(item["owners"]))[camera].get(str(k))
        if row >= GRID or (item["owners"][camera][row][col] != k and most != [row, col]):
            return False
    return True


def hit(kind: str, answer: str, item: dict) -> bool:
    """Whether one reader's ``answer`` to ``item`` counts for the material ``kind``."""
    if kind in ("close_ups", "in_scene"):
        return names_category(answer, item["category"])
    if kind == "instructions":
        return judgement(answer) == "natural"
    return found(answer, item)


def score(key_path: Path, answer_paths: list[Path], agreement: int | None = None) -> dict:
    """The figures of ``answer_paths`` (one file per reader) against ``key_path``."""
    key = json.loads(Path(key_path).read_text())
    kind, items = key["kind"], key["items"]
    readers = [read_answers(p, len(items)) for p in answer_paths]
    need = agreement or default_agreement(len(readers))
    if not 1 <= need <= len(readers):
        raise ValueError(f"agreement {need} outside 1..{len(readers)} readers")
    answers = [[r.get(item["n"], "") for r in readers] for item in items]
    hits = [[hit(kind, a, item) for a in row] for row, item in zip(answers, items, strict=True)]
    detail = [
        {
            "n": item["n"],
            **{k: item[k] for k in ("category", "instruction", "source") if k in item},
            "answers": row,
            "passed": sum(h) >= need,
        }
        for item, row, h in zip(items, answers, hits, strict=True)
    ]
    result = {
        "kind": kind,
        "seed": key["seed"],
        "readers": len(readers),
        "agreement": need,
        "items": len(items),
        "passed": sum(d["passed"] for d in detail),
        "per_reader": [sum(h[r] for h in hits) for r in range(len(readers))],
    }
    if kind == "instructions":
        result["judgements"] = [
            {j: sum(judgement(a[r]) == j for a in answers) for j in JUDGEMENTS}
            for r in range(len(readers))
        ]
    return {**result, "detail": detail}
