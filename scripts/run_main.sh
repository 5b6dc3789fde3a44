#!/usr/bin/env bash
# The main job: installs what is needed, builds, starts the demo (the dynamics node on the
# bundled Panda plus a joint-state source moving it along a smooth trajectory), shows the
# computed torques streaming and one call of each service with its answer, then stops cleanly.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_dependencies.sh
bash scripts/build.sh all
port="${SPATIAL_DYNAMICS_DEMO_PORT:-11411}"
# shellcheck source=scripts/ros_env.sh
source scripts/ros_env.sh "$port"

roslaunch -p "$port" spatial_dynamics demo.launch >build/demo.log 2>&1 &
launch_pid=$!
stop_demo() {
  kill -INT "$launch_pid" 2>/dev/null || true
  for _ in $(seq 100); do kill -0 "$launch_pid" 2>/dev/null || break; sleep 0.1; done
  kill -KILL "$launch_pid" 2>/dev/null || true
  echo "demo stopped (log: build/demo.log)"
}
trap stop_demo EXIT

for _ in $(seq 150); do
  rosservice list 2>/dev/null | grep -q /dynamics/transform_wrench && break
  sleep 0.2
done
rosservice list 2>/dev/null | grep -q /dynamics/transform_wrench || { cat build/demo.log; echo "the node did not start"; exit 1; }

show() {  # prints a command, then runs it
  printf '\n$ %s\n' "$*"
  "$@"
}
echo "== computed torques streaming on /dynamics/computed_torques (effort of 5 messages, then the rate)"
show rostopic echo -n 5 /dynamics/computed_torques/effort
show timeout 3 rostopic hz /dynamics/computed_torques || true

echo
echo "== one call of each service (joints left out take the latest joint_states)"
show rosservice call /dynamics/inverse_dynamics "{}"
show rosservice call /dynamics/inverse_dynamics "{name: [panda_joint2, panda_joint4], acceleration: [1.0, -0.5], external_wrenches: [{header: {frame_id: panda_hand}, wrench: {force: {x: 0.0, y: 0.0, z: -20.0}}}]}"
show rosservice call /dynamics/inverse_dynamics_trajectory "{trajectory: {joint_names: [panda_joint2, panda_joint4], points: [{positions: [0.0, -1.5], time_from_start: {secs: 0}}, {positions: [0.1, -1.4], time_from_start: {secs: 1}}, {positions: [0.3, -1.2], time_from_start: {secs: 2}}]}}"
show rosservice call /dynamics/forward_dynamics "{name: [panda_joint4], effort: [5.0]}"
show rosservice call /dynamics/mass_matrix "{}"
show rosservice call /dynamics/transform_wrench "{wrench: {header: {frame_id: panda_hand}, wrench: {force: {x: 0.0, y: 0.0, z: -10.0}}}, target_frame: panda_link0}"
show rosservice call /dynamics/set_payload "{frame: panda_hand, inertia: {m: 2.0, com: {x: 0.0, y: 0.0, z: 0.1}, ixx: 0.004, iyy: 0.004, izz: 0.002}}"
show rosservice call /dynamics/set_payload "{frame: panda_hand, inertia: {m: 0.0}}"
show rosservice call /dynamics/reload
echo
echo "== a bad request is answered with the culprit named"
show rosservice call /dynamics/inverse_dynamics "{name: [panda_joint9], position: [0.0]}"
