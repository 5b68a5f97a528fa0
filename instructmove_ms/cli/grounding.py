"""``instructmove train-grounding``: train the grounding model on rendered training scenes."""

from __future__ import annotations

import argparse


def _cmd_train(args: argparse.Namespace) -> int:
    from dataclasses import asdict
    from pathlib import Path

    from instructmove_ms.files import write_json, write_text
    from instructmove_ms.grounding import judge, scenes
    from instructmove_ms.grounding.training import Schedule, choose, fit

    out = Path(args.out)
    schedule = Schedule(
        epochs=args.epochs,
        seed=args.seed,
        threads=args.threads,
        text=not args.image_only,
        held_out=args.held_out,
    )
    alternatives = not (args.image_only or args.normal_only)
    taught = scenes.training(Path(args.cache), args.scenes, args.sampler, alternatives=alternatives)
    model, history = fit(taught, schedule, out)
    print(f"checkpoint: {out}; kept epoch {history.kept + 1} of {len(history.losses)}")
    for name, values in asdict(history).items():
        print(f"  {name} per epoch: {', '.join(f'{v:.3f}' for v in values)}")
    if args.judge:
        judged = scenes.stored(Path(args.cache), args.set_version)
        rows = judge.table(judged, choose(model, judged))
        conditions = judge.counterfactuals(model, judged, args.judge, args.set_version)
        found = {**asdict(history), "stored sets": rows, "conditions": conditions}
        write_json(out.with_suffix(".json"), found)
        tables = [judge.markdown(rows), judge.markdown(conditions)]
        write_text(out.with_suffix(".md"), "\n\n".join(tables) + "\n")
        print(judge.markdown([r for r in rows if r["robot"] == judge.POOLED]))
        print(tables[1])
    return 0


def add_parsers(sub: argparse._SubParsersAction) -> None:
    from instructmove_ms.cli.common import _add_set_version
    from instructmove_ms.grounding import SCENES
    from instructmove_ms.grounding.training import Schedule
    from instructmove_ms.sampler import SAMPLER, SAMPLERS

    p = sub.add_parser(
        "train-grounding",
        help="train the grounding model (candidate crops in the 224 x 224 cameras and the "
        "instruction) on rendered training scenes; resumable",
    )
    p.add_argument("--out", default="out/grounding/grounded.pt", help="checkpoint to write")
    p.add_argument(
        "--cache",
        default="out/grounding/renders",
        help="where rendered scenes are kept (default out/grounding/renders)",
    )
    p.add_argument(
        "--scenes",
        type=int,
        default=SCENES,
        help=f"training scenes per family and robot (default {SCENES}, as the shipped model)",
    )
    p.add_argument("--sampler", type=int, choices=SAMPLERS, default=SAMPLER)
    p.add_argument("--epochs", type=int, default=Schedule.epochs)
    p.add_argument("--seed", type=int, default=Schedule.seed, help="same seed, same model")
    p.add_argument(
        "--threads",
        type=int,
        default=Schedule.threads,
        help=f"torch's CPU threads (default {Schedule.threads}; part of what fixes the model)",
    )
    p.add_argument(
        "--held-out",
        type=int,
        default=Schedule.held_out,
        metavar="K",
        help=f"validate on the training seeds divisible by K, never train on them, and keep "
        f"the epoch with the lowest validation loss (default {Schedule.held_out}; 0: none, "
        "the last epoch is kept)",
    )
    p.add_argument(
        "--normal-only",
        action="store_true",
        help="train on the scenes' own instructions alone (by default each scene is taught "
        "under its alternative-target instruction too: the same pictures, another goal named; "
        "--image-only implies this)",
    )
    p.add_argument(
        "--image-only",
        action="store_true",
        help="never read the instruction (the audit's pixel adversary: the image-only twin)",
    )
    p.add_argument(
        "--judge",
        type=int,
        default=0,
        metavar="N",
        help="also measure its choices on the stored sets, and on their first N episodes "
        "under every condition (writes CHECKPOINT.json and .md)",
    )
    _add_set_version(p)
    p.set_defaults(func=_cmd_train)
