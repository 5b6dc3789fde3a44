#!/usr/bin/env bash
# The node's own overhead on loopback, with a master of its own: the dynamics node (bundled Panda)
# and a do-nothing InverseDynamics server of the same message sizes; InverseDynamics round trips
# to both in interleaved repeats, then joint_states at 1 kHz and the latency to ~computed_torques.
# Prints the figures (also written to build/node_overhead.md). Bounded in time and calls.
#   run_node_overhead.sh [seconds of joint_states, default 20] [calls per repeat, default 250]
#                        [repeats per service, default 40]
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-20}"
calls="${2:-250}"
repeats="${3:-40}"
bash scripts/install_dependencies.sh
bash scripts/build.sh dynamics_node empty_service_node node_overhead
port="${SPATIAL_DYNAMICS_OVERHEAD_PORT:-11621}"
# shellcheck source=scripts/ros_env.sh
source scripts/ros_env.sh "$port"
roslaunch -p "$port" spatial_dynamics dynamics.launch >build/node_overhead_node.log 2>&1 &
launch_pid=$!
./build/devel/lib/spatial_dynamics/empty_service_node __name:=empty_service >build/node_overhead_empty.log 2>&1 &
empty_pid=$!
trap 'kill -INT $empty_pid $launch_pid 2>/dev/null; wait $empty_pid $launch_pid 2>/dev/null || true' EXIT
./build/devel/lib/spatial_dynamics/node_overhead --seconds "$seconds" --calls "$calls" --repeats "$repeats" --rate 1000 \
  --out build/node_overhead.md
