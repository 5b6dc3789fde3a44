#!/usr/bin/env bash
# Configures and builds the catkin package standalone.
#   build.sh [-B DIR] [-DNAME=VALUE ...] [make targets ...]
# DIR defaults to build/; -D arguments go to cmake (e.g. -DSPATIAL_DYNAMICS_SANITIZE=address,undefined,
# -DCMAKE_BUILD_TYPE=RelWithDebInfo; the build type defaults to Release). The compiler's output goes
# to DIR/build.log; on failure its end is printed.
set -euo pipefail
cd "$(dirname "$0")/.."
# Debian's catkin needs the system interpreter (with catkin_pkg), not one earlier on PATH.
export PATH="/usr/bin:$PATH"
build_dir=build
cmake_args=(-DCMAKE_BUILD_TYPE=Release)
targets=()
while [ $# -gt 0 ]; do
  case "$1" in
    -B) build_dir="$2"; shift 2 ;;
    -D*) cmake_args+=("$1"); shift ;;
    *) targets+=("$1"); shift ;;
  esac
done
mkdir -p "$build_dir"
# Compiled objects are reused across build directories and fresh clones (ccache, installed by
# install_dependencies.sh): paths below the repository root are hashed relative to it.
if command -v ccache >/dev/null 2>&1; then
  export CCACHE_BASEDIR="$PWD" CCACHE_NOHASHDIR=1
  cmake_args+=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
fi
echo "building ${targets[*]:-all} in $build_dir/ ..."
if ! { cmake -S . -B "$build_dir" -DPYTHON_EXECUTABLE=/usr/bin/python3 "${cmake_args[@]}" &&
       make -C "$build_dir" -j"$(nproc)" --no-print-directory "${targets[@]}"; } >"$build_dir/build.log" 2>&1; then
  tail -n 60 "$build_dir/build.log"
  echo "the build failed; the whole output is in $build_dir/build.log" >&2
  exit 1
fi
