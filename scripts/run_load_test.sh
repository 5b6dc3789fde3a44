#!/usr/bin/env bash
# Load test on loopback: starts the node (bundled Panda) with a master of its own, drives it with
# joint_states at 1 kHz and 8 concurrent service clients for 60 s (arguments override: seconds,
# clients), and prints the figures (also written to build/load_test.md). Bounded in time and calls.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
clients="${2:-8}"
bash scripts/install_dependencies.sh
bash scripts/build.sh dynamics_node load_test
port="${SPATIAL_DYNAMICS_LOAD_PORT:-11611}"
# shellcheck source=scripts/ros_env.sh
source scripts/ros_env.sh "$port"
roslaunch -p "$port" spatial_dynamics dynamics.launch >build/load_test_node.log 2>&1 &
launch_pid=$!
trap 'kill -INT $launch_pid 2>/dev/null; wait $launch_pid 2>/dev/null || true' EXIT
node_pid=""
for _ in $(seq 150); do
  node_pid=$(pgrep -f "spatial_dynamics/dynamics_node.*__name:=dynamics" | head -n 1 || true)
  [ -n "$node_pid" ] && break
  sleep 0.2
done
[ -n "$node_pid" ] || { cat build/load_test_node.log; echo "the node did not start"; exit 1; }
./build/devel/lib/spatial_dynamics/load_test --node-pid "$node_pid" --seconds "$seconds" --clients "$clients" \
  --rate 1000 --out build/load_test.md
