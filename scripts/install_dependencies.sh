#!/usr/bin/env bash
# Installs the Debian 12 packages the package needs to build, run and test, plus any packages
# given as arguments (scripts/install_fuzzing_dependencies.sh passes clang's).
# apt-get runs as root, or through sudo otherwise; nothing is installed when all are present.
set -euo pipefail

packages=(
  build-essential cmake ccache catkin python3-catkin-pkg
  ros-core-dev libroscpp-dev libroslib-dev librostest-dev python3-rostest
  liburdfdom-dev liburdfdom-headers-dev libconsole-bridge-dev libeigen3-dev libboost-dev
  googletest libgtest-dev
  liborocos-kdl-dev libkdl-parser-dev libmujoco-dev
  ros-message-generation python3-genpy
  libstd-msgs-dev libgeometry-msgs-dev libsensor-msgs-dev libnav-msgs-dev libtrajectory-msgs-dev libstd-srvs-dev libdiagnostic-msgs-dev
  libdiagnostic-updater-dev libtf2-dev libtf2-ros-dev libnodeletlib-dev libnodeletlib-tools
  python3-rospy python3-roslaunch python3-rosservice python3-rostopic python3-rosnode python3-rospkg
  rosbash rospack-tools
  python3-std-msgs python3-geometry-msgs python3-sensor-msgs python3-trajectory-msgs python3-std-srvs
  python3-numpy python3-setuptools python3-nose pybind11-dev python3-pybind11 python3-matplotlib
)
packages+=("$@")

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

if [ "$(id -u)" -eq 0 ]; then
  as_root=()
else
  as_root=(sudo)
fi
echo "Installing: ${missing[*]}"
"${as_root[@]}" apt-get update
DEBIAN_FRONTEND=noninteractive "${as_root[@]}" apt-get install -y --no-install-recommends "${missing[@]}"
