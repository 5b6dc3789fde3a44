# Sourced by the scripts that start ROS processes: the built package's environment and a ROS
# master of our own on port $1 (so that a running ROS system is left alone).
export PATH="/usr/bin:$PATH"
set +u  # the ROS environment scripts read unset variables
# shellcheck disable=SC1091
source build/devel/setup.bash
set -u
export ROS_MASTER_URI="http://localhost:$1" ROS_HOSTNAME=localhost
