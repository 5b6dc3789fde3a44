#!/usr/bin/env bash
# The main job: installs what is needed, builds, and prints the gravity torques of the bundled
# default robot (the Panda) at two configurations. Pass a URDF path to use another robot.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_dependencies.sh
bash scripts/build.sh print_gravity_torques
./build/devel/lib/spatial_dynamics/print_gravity_torques "$@"
