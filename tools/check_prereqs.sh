#!/bin/sh
# Check what `make setup` needs before it starts, and say plainly what is missing.
# Usage: tools/check_prereqs.sh PYTHON
python=${1:-python3}
missing=0

fail() {
    echo "setup: $1" >&2
    missing=1
}

if ! command -v "$python" >/dev/null 2>&1; then
    fail "'$python' not found. Install Python 3.11 or 3.12 (the ROS 2 Jazzy wheels exist for those), or run 'make PYTHON=/path/to/python3.12 ...'."
elif ! version=$("$python" -c 'import platform; print(platform.python_version())' 2>&1) || [ -z "$version" ]; then
    fail "'$python' does not run ($(command -v "$python"): ${version:-no output}); a broken interpreter or version-manager shim? Run 'make PYTHON=/path/to/python3.12 ...'."
elif ! "$python" -c 'import sys; sys.exit(0 if sys.version_info[:2] in ((3, 11), (3, 12)) else 1)' >/dev/null 2>&1; then
    fail "'$python' is Python $version; the ROS 2 Jazzy wheels need 3.11 or 3.12. Run 'make PYTHON=/path/to/python3.12 ...'."
elif ! "$python" -c 'import venv, ensurepip' >/dev/null 2>&1; then
    fail "'$python' lacks the venv/ensurepip modules (on Debian/Ubuntu: apt install python3-venv)."
elif ! "$python" -c 'import sysconfig, os, sys; sys.exit(0 if os.path.exists(os.path.join(sysconfig.get_paths()["include"], "Python.h")) else 1)' >/dev/null 2>&1; then
    fail "Python headers (Python.h) not found for '$python'; allocator_msgs compiles C extensions (on Debian/Ubuntu: apt install python3-dev)."
fi
if ! command -v cmake >/dev/null 2>&1; then
    fail "cmake not found (3.16 or newer); it builds the allocator_msgs interface package."
fi
if ! command -v cc >/dev/null 2>&1 && ! command -v gcc >/dev/null 2>&1; then
    fail "no C compiler (cc/gcc) found; the generated interface code is C."
fi
if ! command -v c++ >/dev/null 2>&1 && ! command -v g++ >/dev/null 2>&1; then
    fail "no C++ compiler (c++/g++) found; rosidl also generates C++ type support."
fi
exit $missing
