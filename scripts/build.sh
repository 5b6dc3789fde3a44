#!/usr/bin/env bash
# Configures and builds the catkin package standalone into build/ (extra arguments: make targets).
set -euo pipefail
cd "$(dirname "$0")/.."
# Debian's catkin needs the system interpreter (with catkin_pkg), not one earlier on PATH.
export PATH="/usr/bin:$PATH"
cmake -S . -B build -DPYTHON_EXECUTABLE=/usr/bin/python3 -DCMAKE_BUILD_TYPE=Release >/dev/null
make -C build -j"$(nproc)" --no-print-directory "$@"
