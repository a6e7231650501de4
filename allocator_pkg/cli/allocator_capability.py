"""allocator-capability: the capability envelope of a vehicle as a plot and a table.

``allocator-capability config.yaml [--out folder]`` writes ``<vehicle>_capability.png`` (the
largest request held per direction in a plane of two controlled DOFs, polar for surge and
sway, for the nominal vehicle and every single-actuator failure) and ``<vehicle>_capability.csv``
(the same numbers); ``--all-methods`` adds ``<vehicle>_<method>_capability.png`` and ``.csv``
for each group of registered methods whose constraints give another capability than the
file's method. The numbers come from :class:`~allocator_pkg.capability.envelope.Capability`.

``allocator-capability --dnv-level1 VESSEL.yaml PARTICULARS.yaml [--out folder]`` writes the
DNV-ST-0111 Level 1 DP capability report (plots, tables, summary): the files read once
(:mod:`~allocator_pkg.dp.vessel_files`), the complete result of :mod:`~allocator_pkg.dp.level1`,
then the report of :mod:`~allocator_pkg.dp.report.files`; ``--dnv-level2`` the same at Level 2
(:mod:`~allocator_pkg.dp.level2`) with a plot of Level 1 against it; ``--site SITE.yaml`` gives
Level 2 a site environment in place of Table 2-1 (:mod:`~allocator_pkg.dp.inputs.site`);
``--dnv-level3`` the time-domain Level 3 of :mod:`~allocator_pkg.dp.level3.study` (closed-loop
runs on a process pool or a Dask cluster), its criteria from ``--level3-criteria FILE``
(:mod:`~allocator_pkg.dp.level3.criteria_file`) with ``--seeds``, ``--position-limit``,
``--heading-limit``, ``--settle`` and ``--duration`` in place of the file's keys.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from ..allocation.allocator import Allocator
from ..capability.envelope import Capability, differing_methods, reachable
from ..capability.report.envelope_files import write_envelopes
from ..configuration.file_keys import key_named
from ..configuration.parameters import load_vehicle
from ..dp.capability_result import CapabilityResult
from ..dp.level1 import Level1
from ..dp.level2 import Level2
from ..dp.level3.case import CRITERIA_KEYS, Criteria
from ..dp.level3.criteria_file import read_criteria
from ..dp.level3.engine import CaseLost, Interrupted
from ..dp.level3.screening import screening_table
from ..dp.level3.study import BASE_SCENARIO, JOURNAL, Level3Inputs, study
from ..dp.report.files import write_report
from ..dp.report.level3_report import Screening, write_level3
from ..dp.vessel_files import read_vessel_files
from ..methods import METHODS
from ..vehicle.config import DOF_NAMES

INTERRUPTED = 130
"""The exit status of a run stopped by SIGINT (128 + the signal's number, as a shell gives)."""
CRITERIA_OPTIONS = (("--seeds", "seeds", int), ("--position-limit", "position_limit", float),
                    ("--heading-limit", "heading_limit_deg", float), ("--settle", "settle", float),
                    ("--duration", "duration", float))
"""The options that override a key of the Level 3 criteria file (:data:`CRITERIA_KEYS`: its default,
unit and text), each the value of its key when given."""


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="allocator-capability", description=__doc__.split("\n\n")[0])
    parser.add_argument("config", nargs="?", help="vehicle params file")
    parser.add_argument("--out", default=".", help="folder for <vehicle>_capability.png and .csv")
    parser.add_argument("--step", type=float, default=5.0, help="degrees between directions (default %(default)s)")
    parser.add_argument("--yaw-moment", type=float, default=0.0, help="yaw moment held [N m] (default 0)")
    parser.add_argument("--speed", type=float, default=2.0, help="surge speed for control surfaces [m/s]")
    parser.add_argument("--method", choices=list(METHODS), help="default: the file's")
    parser.add_argument("--plane", nargs=2, metavar=("X", "Y"), choices=DOF_NAMES,
                        help="the two DOFs of the plot (default: surge sway, else the first two controlled)")
    parser.add_argument("--all-methods", action="store_true",
                        help="also <vehicle>_<method>_capability.png and .csv for each group of registered methods "
                             "whose constraints give another capability than the file's method")
    parser.add_argument("--dnv-level1", nargs=2, metavar=("VESSEL", "PARTICULARS"),
                        help="DNV-ST-0111 Level 1 DP capability report of a vehicle params file and a particulars "
                             "file (config/particulars/): <vehicle>_dp_l1_report.md, plots, tables")
    parser.add_argument("--dnv-level2", nargs=2, metavar=("VESSEL", "PARTICULARS"),
                        help="the same at Level 2 with the vessel's own data (<vehicle>_dp_l2...), and a plot of "
                             "Level 1 against Level 2")
    parser.add_argument("--site", metavar="SITE",
                        help="with --dnv-level2 or --dnv-level3: a site environment file (wind, hs, tp or tz, "
                             "current over the capability numbers) in place of Table 2-1 and of the particulars' "
                             "level2.site")
    parser.add_argument("--heading-step", "--headings", type=float, default=10.0,
                        help="degrees between headings for --dnv-level1/2/3 (default %(default)s)")
    add_level3_arguments(parser)
    arguments = parser.parse_args(argv)
    if arguments.site and not (arguments.dnv_level2 or arguments.dnv_level3):
        parser.error("--site goes with --dnv-level2 or --dnv-level3")
    if arguments.dnv_level3:
        return level3_command(arguments)
    if arguments.dnv_level1 or arguments.dnv_level2:
        return _dnv(arguments)
    if arguments.config is None:
        parser.error("a vehicle params file, or --dnv-level1/--dnv-level2 VESSEL PARTICULARS")
    vehicle = load_vehicle(arguments.config)
    plane = tuple(arguments.plane) if arguments.plane else None
    try:
        capability = Capability(vehicle, arguments.method, arguments.speed, plane)
    except ValueError as error:
        print(f"allocator-capability: {error}", file=sys.stderr)
        return 2
    for warning in Allocator(reachable(vehicle), method=capability.method).warnings:
        print(f"allocator-capability: warning: {warning}", file=sys.stderr)
    stem = Path(arguments.config).stem
    _print(write_envelopes(capability, Path(arguments.out), stem, "", capability.method, arguments.step,
                           arguments.yaw_moment))
    if arguments.all_methods:
        for names in differing_methods(vehicle, capability.method):
            other = Capability(vehicle, names[0], arguments.speed, plane)
            _print(write_envelopes(other, Path(arguments.out), stem, f"_{names[0]}", ", ".join(names),
                                   arguments.step, arguments.yaw_moment))
    return 0


def add_level3_arguments(parser: argparse.ArgumentParser) -> None:
    """The options of ``--dnv-level3`` on the ``allocator-capability`` parser."""
    parser.add_argument("--dnv-level3", nargs=2, metavar=("VESSEL", "PARTICULARS"),
                        help="DNV-ST-0111 Level 3 as read here: seeded closed-loop time-domain runs per heading, "
                             "condition and redundancy group (<vehicle>_dp_l3..., cases.jsonl)")
    parser.add_argument("--level3-criteria", metavar="FILE", type=Path,
                        help="--dnv-level3: the criteria file (config/level3/criteria.yaml: limits, durations, "
                             "seeds, quantile, bootstrap, post-failure limits); absent keys at their defaults")
    engine = parser.add_mutually_exclusive_group()
    engine.add_argument("--workers", type=int, help="--dnv-level3: local worker processes (default: the CPU count)")
    engine.add_argument("--scheduler", metavar="ADDRESS",
                        help="--dnv-level3: run the cases on the Dask distributed scheduler at ADDRESS")
    parser.add_argument("--resume", action="store_true",
                        help="--dnv-level3: keep the finished cases of DIR/cases.jsonl and run only the rest")
    for option, name, kind in CRITERIA_OPTIONS:
        key = key_named(CRITERIA_KEYS, name)
        unit = f" [{key.unit}]" if key.unit else ""
        parser.add_argument(option, type=kind, dest=name,
                            help=f"--dnv-level3: {key.text}{unit}, in place of the criteria file's {name} "
                                 f"(default: the file's, else {key.documented_default()})")
    parser.add_argument("--scenario", type=Path, default=BASE_SCENARIO,
                        help="--dnv-level3: the dp_vessel scenario giving controller gains, thruster time constant "
                             "and the environment's variations (default config/scenarios/dp_station_keeping.yaml)")
    parser.add_argument("--no-progress", action="store_true", help="--dnv-level3: no progress bar")


def level3_command(arguments: argparse.Namespace) -> int:
    """``--dnv-level3``: check every input, run the cases, write the outputs; the summary, the
    scope and criteria lines and the paths on stdout."""
    vessel, particulars = arguments.dnv_level3
    out = Path(arguments.out)
    try:
        inputs = Level3Inputs(Path(vessel), Path(particulars), arguments.scenario,
                              Path(arguments.site) if arguments.site else None, arguments.method,
                              arguments.heading_step, level3_criteria(arguments))
        prepared, result, finished = study(inputs, out, arguments.workers, arguments.scheduler, arguments.resume,
                                           not arguments.no_progress)
    except Interrupted as interrupted:
        print(f"allocator-capability: {interrupted}", file=sys.stderr)
        return INTERRUPTED
    except (ValueError, OSError) as error:             # a ConfigError, a ScenarioError too
        print(f"allocator-capability: {error}", file=sys.stderr)
        return 2
    except CaseLost as error:
        print(f"allocator-capability: {error}; rerun with --resume", file=sys.stderr)
        return 1
    paths = write_level3(prepared, result, finished, out, Screening(*screening_table(prepared.setup, finished)))
    print(result.summary_line())
    print(result.scope)
    print(result.notes[0])
    for path in [out / JOURNAL, *paths]:
        print(path)
    return 0


def level3_criteria(arguments: argparse.Namespace) -> Criteria:
    """The criteria of ``--level3-criteria`` (or the defaults) with the options given in place of
    their keys."""
    overrides = {name: getattr(arguments, name) for _, name, _ in CRITERIA_OPTIONS
                 if getattr(arguments, name) is not None}
    return read_criteria(arguments.level3_criteria, overrides)


def _print(paths: list[Path]) -> None:
    for path in paths:
        print(path)


def _dnv(arguments: argparse.Namespace) -> int:
    """--dnv-level1/2: the report of :func:`dnv_report`, the summary and scope lines on stdout."""
    level = 1 if arguments.dnv_level1 else 2
    vessel, particulars = arguments.dnv_level1 or arguments.dnv_level2
    try:
        result, paths = dnv_report(vessel, particulars, arguments.out, arguments.heading_step, arguments.method,
                                   level, arguments.site)
    except ValueError as error:                 # a ConfigError too
        print(f"allocator-capability: {error}", file=sys.stderr)
        return 2
    print(result.summary_line())
    print(result.scope)
    for path in paths:
        print(path)
    return 0


def dnv_report(vessel: str | Path, particulars: str | Path, out: str | Path, step_deg: float = 10.0,
               method: str | None = None, level: int = 1,
               site: str | Path | None = None) -> tuple[CapabilityResult, list[Path]]:
    """Level 1 or 2 of a vehicle file and a particulars file (Level 2: with the site environment
    file ``site`` if given): the files read once, the complete result (Level 2's with the Level 1
    result it is drawn against), then the report; (result, paths written)."""
    files = read_vessel_files(vessel, particulars, site)
    analysis = (Level1(files.vehicle, files.particulars, method) if level == 1 else
                Level2(files.vehicle, files.particulars, method, files.site))
    lower = () if level == 1 else (Level1(files.vehicle, files.particulars, method).run(step_deg),)
    result = analysis.run(step_deg, lower)
    return result, write_report(out, files, analysis, result)


if __name__ == "__main__":
    sys.exit(main())
