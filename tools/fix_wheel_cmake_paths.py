"""Point the ROS wheels' CMake exports at this venv's Python and NumPy headers.

The ros-jazzy-* wheels were built in manylinux containers and their exported CMake
targets (``share/*/cmake/*.cmake``) name include folders such as
``/opt/python/cp311-cp311/include/python3.11``. CMake refuses imported targets whose
include folders do not exist, so building allocator_msgs against them fails until the
paths name this interpreter's headers. Idempotent: a second run changes nothing.
"""

import re
import sys
import sysconfig
from pathlib import Path

import numpy

PYTHON_INCLUDE = re.compile(r"/opt/python/cp\d+-cp\d+/include/python[\d.]+t?")
NUMPY_INCLUDE = re.compile(r"/opt/python/cp\d+-cp\d+/lib/python[\d.]+t?/site-packages/numpy/(_core/)?include")


def main() -> int:
    share = Path(sys.prefix) / "share"
    python_include = sysconfig.get_paths()["include"]
    numpy_include = numpy.get_include()
    changed = 0
    for path in share.glob("**/*.cmake"):
        text = path.read_text()
        if "/opt/python/" not in text:
            continue
        fixed = NUMPY_INCLUDE.sub(numpy_include, text)
        fixed = PYTHON_INCLUDE.sub(python_include, fixed)
        if fixed != text:
            path.write_text(fixed)
            changed += 1
    leftover = [str(p) for p in share.glob("**/*.cmake") if "/opt/python/" in p.read_text()]
    if leftover:
        print("fix_wheel_cmake_paths: unrecognised /opt/python paths remain in:", *leftover, sep="\n  ")
        return 1
    print(f"fix_wheel_cmake_paths: {changed} CMake file(s) now use {python_include} and {numpy_include}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
