#!/usr/bin/env bash
# Configures and builds the catkin package standalone into build/ (extra arguments: make targets).
# The compiler's output goes to build/build.log; on failure its end is printed.
set -euo pipefail
cd "$(dirname "$0")/.."
# Debian's catkin needs the system interpreter (with catkin_pkg), not one earlier on PATH.
export PATH="/usr/bin:$PATH"
mkdir -p build
echo "building ($*) ..."
if ! { cmake -S . -B build -DPYTHON_EXECUTABLE=/usr/bin/python3 -DCMAKE_BUILD_TYPE=Release &&
       make -C build -j"$(nproc)" --no-print-directory "$@"; } >build/build.log 2>&1; then
  tail -n 60 build/build.log
  echo "the build failed; the whole output is in build/build.log" >&2
  exit 1
fi
