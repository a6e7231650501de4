"""allocator-explicit: the regions of the explicit method (survey 4.1) enumerated offline.

``allocator-explicit precompute config.yaml [--out file.npz] [--speed S]`` enumerates the
regions of a small vehicle (:func:`~allocator_pkg.methods.explicit_regions.precompute`, with
control surfaces' ranges at ``--speed``) and writes them to a file.

The file holds the active sets and the fingerprint of the data they were computed for (T, W,
Q, beta); the node builds their laws when it sets the method up (``explicit.regions``) and
refuses a file computed for other data. A region missing from the file is still found online
(moves, OSQP), then cached: the table only spares KKT solves while allocating.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

from ..configuration.parameters import vehicle_from_parameters
from ..configuration.params_file import read_parameters
from ..methods.explicit_regions import precompute
from ..vehicle.config import ConfigError


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="allocator-explicit", description=__doc__.split("\n\n")[0])
    commands = parser.add_subparsers(dest="command", required=True)
    command = commands.add_parser("precompute", help="enumerate the regions of a vehicle into a file")
    command.add_argument("config", type=Path, help="vehicle params file")
    command.add_argument("--out", type=Path, default=None, help="default: <config>.regions.npz beside it")
    command.add_argument("--speed", type=float, default=2.0, help="flow speed for control surfaces' ranges [m/s]")
    arguments = parser.parse_args(argv)
    try:
        parameters = read_parameters(arguments.config)
        parameters["explicit.regions"] = ""         # the file this writes may be missing or stale
        vehicle = vehicle_from_parameters(parameters)
        keys, tried, seconds, law = precompute(vehicle, arguments.speed)
    except (ConfigError, ValueError, OSError) as error:
        print(f"allocator-explicit: {error}", file=sys.stderr)
        return 1
    out = arguments.out or arguments.config.with_suffix(".regions.npz")
    np.savez_compressed(out, keys=np.array(keys, dtype=np.int64), fingerprint=np.array(law.fingerprint),
                        tried=np.array(tried), seconds=np.array(seconds))
    print(f"{arguments.config}: {len(keys)} regions of {tried} active sets in {seconds:.1f} s -> {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
