"""``instructmove doctor``: what works on this machine, one line per finding."""

from __future__ import annotations

import argparse
import json


def _cmd_doctor(args: argparse.Namespace) -> int:
    from instructmove_ms import doctor

    findings = doctor.run_checks()
    if args.json:
        print(json.dumps(doctor.as_json(findings), indent=1))
    else:
        for finding in findings:
            print(finding.line())
    broken = doctor.broken(findings)
    if broken and not args.json:
        print(f"broken: {', '.join(f.name for f in broken)}")
    return 1 if broken else 0


def add_parsers(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "doctor",
        help="what works on this machine: packages, floating point, physics, rendering, CUDA "
        "and GPU physics, the asset library, the stored sets, extras, workers",
    )
    p.add_argument("--json", action="store_true", help="the findings as one JSON object")
    p.set_defaults(func=_cmd_doctor)
