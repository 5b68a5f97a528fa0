"""``instructmove assets``: the object library."""

from __future__ import annotations

import argparse
import json
import sys

from instructmove_ms.cli.common import _add_group


def _assets(args: argparse.Namespace):
    """(the snapshot, its instances of the asked category or all)."""
    from instructmove_ms.assets import load_snapshot

    catalog = load_snapshot(args.snapshot)
    return catalog, [
        i for i in catalog.instances if not args.category or i.category == args.category
    ]


def _cmd_assets_list(args: argparse.Namespace) -> int:
    from instructmove_ms.assets.annotations import annotate
    from instructmove_ms.sampler import split_of

    catalog, instances = _assets(args)
    for inst in instances:
        record = annotate(inst, split_of(inst, catalog))
        if args.format == "jsonl":
            print(json.dumps(record))
        else:
            print(
                f"{inst.uuid}  {inst.category:18s} {'/'.join(inst.colors):18s} "
                f"{inst.material:9s} {inst.height * 100:5.1f} cm  {record['split']}"
            )
    return 0


TRIAL_TARGET = 0.95
INSTANCES_PER_CATEGORY = 10  # in the default snapshot


def _cmd_assets_check(args: argparse.Namespace) -> int:
    from tqdm import tqdm

    from instructmove_ms.assets.quality import check_instances

    _, instances = _assets(args)
    by_category: dict[str, list] = {}
    for inst in instances:
        by_category.setdefault(inst.category, []).append(inst)
    failed = 0
    for category in tqdm(sorted(by_category), desc="checking", unit="category"):
        for result in check_instances(by_category[category]):
            if not result.ok:
                failed += 1
                tqdm.write(f"FAIL {result.category} {result.uuid}: {'; '.join(result.failures)}")
    print(f"{len(instances) - failed}/{len(instances)} instances pass the quality checks")
    if args.trials:
        from instructmove_ms.assets.grasp_trial import grasp_trial

        results = []
        for category in tqdm(sorted(by_category), desc="grasp trials", unit="category"):
            results += grasp_trial(by_category[category])
        passed = sum(r.passed for r in results)
        for r in results:
            if not r.passed:
                tqdm.write(f"NO GRASP {r.category} {r.uuid} after {r.tries} tries")
        rate = passed / max(1, len(results))
        print(
            f"grasp trials: {passed}/{len(results)} graspable instances picked up ({rate:.1%}; "
            f"target >= {TRIAL_TARGET:.0%})"
        )
        failed += rate < TRIAL_TARGET
    return 1 if failed else 0


def _cmd_assets_sheet(args: argparse.Namespace) -> int:
    from pathlib import Path

    from tqdm import tqdm

    from instructmove_ms.assets.sheet import contact_sheet, recognition_sheet

    if args.recognition:
        for path in recognition_sheet(_assets(args)[1], Path(args.recognition)):
            print(path)
        return 0
    groups: dict[str, list] = {}
    for inst in _assets(args)[1]:
        groups.setdefault(inst.super_category, []).append(inst)
    for name in tqdm(sorted(groups), desc="contact sheets", unit="sheet"):
        path = contact_sheet(groups[name], Path(args.out) / f"{name}.png")
        tqdm.write(str(path))
    return 0


def _cmd_assets_build(args: argparse.Namespace) -> int:
    from tqdm import tqdm

    from instructmove_ms.assets import snapshot as snap
    from instructmove_ms.assets.generators import GENERATORS

    categories = sorted(GENERATORS)
    shipped = args.name in snap.SHIPPED
    frozen = snap.SHIPPED[args.name] if shipped else snap.Frozen(textures=not args.plain)
    entries = []
    for category in tqdm(categories, desc="generating", unit="category"):
        entries += snap.build_entries([category], args.per_category, frozen)
    folder = snap.package_snapshot_dir() if shipped else snap.user_snapshot_dir()
    released_path = snap.snapshot_path(args.name) if shipped else None
    if released_path is not None:
        released = json.loads(released_path.read_text())["instances"]
        if released != entries:
            first = (
                f"{len(entries)} instances, not {len(released)}"
                if len(entries) != len(released)
                else next(
                    f"{e['category']} #{e['index']}"
                    for e, r in zip(entries, released, strict=True)
                    if e != r
                )
            )
            raise ValueError(
                f"snapshot {args.name!r} ships with a released benchmark and would change "
                f"({first}): a changed generator is a new library revision (@revised), "
                "frozen as a new snapshot (--name NEW)"
            )
    path = snap.write_snapshot(folder / f"{args.name}.json", args.name, entries, frozen)
    print(
        f"snapshot {args.name!r}: {len(entries)} instances of {len(categories)} categories "
        f"({'textured' if frozen.textures else 'plain'}, library revision {frozen.library}) "
        f"-> {path}"
    )
    if shipped:  # other snapshots' colours are rendered on use
        from instructmove_ms.assets.appearance import table_path
        from instructmove_ms.assets.photometry import write_table
        from instructmove_ms.assets.uv_meshes import write_meshes

        write_meshes()

        snap.load_snapshot.cache_clear()
        instances = snap.load_snapshot(args.name).instances
        print(f"rendered colours -> {write_table(instances, table_path(args.name))}")
    return 0


def _cmd_assets_rehash(args: argparse.Namespace) -> int:
    from instructmove_ms.assets.snapshot import rehash

    count, kept = rehash(args.name)
    print(f"snapshot {args.name!r}: {count} instances re-hashed, {kept} stored colours kept")
    return 0


def _cmd_assets_import(args: argparse.Namespace) -> int:
    from pathlib import Path

    from instructmove_ms.assets.snapshot import import_folder

    report = import_folder(Path(args.source), args.name, args.extend or None)
    for asset_id, repairs in report.repaired:
        print(f"repaired {asset_id}: {'; '.join(repairs)}", file=sys.stderr)
    for asset_id, failures in report.rejected:
        print(f"left out {asset_id}: {'; '.join(failures)}", file=sys.stderr)
    print(f"snapshot {args.name!r} -> {report.path} ({len(report.rejected)} assets left out)")
    return 1 if report.rejected else 0


def add_parsers(sub: argparse._SubParsersAction) -> None:
    from instructmove_ms.assets.snapshot import DEFAULT_SNAPSHOT

    assets = _add_group(sub, "assets", "the object library")
    p = assets.add_parser("build", help="generate the library and freeze it as a snapshot")
    p.add_argument(
        "--name",
        default=DEFAULT_SNAPSHOT,
        help=f"snapshot name (default: {DEFAULT_SNAPSHOT}, the shipped one, which a build may "
        "not change; another name writes a snapshot of your own)",
    )
    p.add_argument("--per-category", type=int, default=INSTANCES_PER_CATEGORY)
    p.add_argument(
        "--plain",
        action="store_true",
        help="instances without their textures (the shipped snapshot knows its own look "
        "and library revision; others are built at the newest)",
    )
    p.set_defaults(func=_cmd_assets_build)
    p = assets.add_parser(
        "rehash", help="re-hash a snapshot written by an older identity scheme (same assets)"
    )
    p.add_argument("name", help="snapshot name")
    p.set_defaults(func=_cmd_assets_rehash)
    p = assets.add_parser("import", help="import a folder of meshes + metadata.json")
    p.add_argument("source", help="folder with metadata.json and the mesh files")
    p.add_argument("--name", required=True, help="name of the new snapshot")
    p.add_argument(
        "--extend", default=DEFAULT_SNAPSHOT, help="snapshot to add the assets to ('' for none)"
    )
    p.set_defaults(func=_cmd_assets_import)
    for name, func, text in (
        ("list", _cmd_assets_list, "print every asset with its annotations"),
        ("check", _cmd_assets_check, "run the quality checks (geometry, size, settling, grasps)"),
        ("sheet", _cmd_assets_sheet, "write a labelled contact sheet PNG per super-category"),
    ):
        p = assets.add_parser(name, help=text)
        p.add_argument("--snapshot", default=DEFAULT_SNAPSHOT, help="(default: %(default)s)")
        p.add_argument("--category", default=None, help="only this category")
        p.set_defaults(func=func)
        if name == "list":
            p.add_argument("--format", choices=("table", "jsonl"), default="table")
        if name == "check":
            p.add_argument(
                "--trials",
                action="store_true",
                help="also pick every graspable instance up with a floating gripper",
            )
        if name == "sheet":
            p.add_argument("--out", default="out/sheets", help="folder for the PNGs")
            p.add_argument(
                "--recognition",
                default=None,
                metavar="OUT",
                help="instead: one unlabelled close-up per category (OUT/recognition.png) and "
                "its labelled key (OUT/recognition_key.png), to check each object reads as its "
                "name",
            )
