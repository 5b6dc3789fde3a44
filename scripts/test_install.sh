#!/usr/bin/env bash
# Installs the package into a scratch catkin workspace and uses it from there, as another package
# would; ends with the line "N passed, N failed" and fails when any check failed.
#   test_install.sh            (the workspaces go to build/install_test/, removed first and at the
#                              end; the logs stay there)
# 1. copies the package (its git-tracked and untracked-but-not-ignored files) to
#    build/install_test/ws/src/ and runs Debian's `catkin_make install` there (no tests, no benchmark);
# 2. moves the workspace's src/, build/ and devel/ away (to build/install_test/moved/), so that
#    only the install space is left, and sources nothing but install/setup.bash;
# 3. checks the install space's files, `rosrun spatial_dynamics print_gravity_torques` (its default
#    URDF from the share directory, and a clear error without ROS_PACKAGE_PATH);
# 4. builds test/downstream/dynamics_user in a second workspace (build/install_test/user_ws)
#    against the install space;
# 5. starts `roslaunch spatial_dynamics dynamics.launch` with a master of its own on port
#    $SPATIAL_DYNAMICS_INSTALL_TEST_PORT (default 11511) and runs the downstream package's C++ and
#    Python checks against that node.
# Every wait is bounded; the node and its master are stopped on exit. Logs: build/install_test/*.log.
set -uo pipefail
cd "$(dirname "$0")/.." || exit 1
# shellcheck source=scripts/test_common.sh
source scripts/test_common.sh

root=$PWD
base="$root/build/install_test"
ws="$base/ws"
user_ws="$base/user_ws"
install="$ws/install"
port="${SPATIAL_DYNAMICS_INSTALL_TEST_PORT:-11511}"
build_timeout="${SPATIAL_DYNAMICS_INSTALL_TEST_BUILD_TIMEOUT:-2400}"  # seconds, per catkin_make
started=$SECONDS

passed=0
failed=0
pass() {
  echo "PASS $1"
  passed=$((passed + 1))
}
# fail_check WHAT [LOG]: one failure; the end of LOG, when given, goes to stderr.
fail_check() {
  echo "FAIL $1"
  failed=$((failed + 1))
  if [ $# -gt 1 ] && [ -f "$2" ]; then
    echo "--- end of $2:" >&2
    tail -n 40 "$2" >&2
  fi
}
finish() {
  # The workspaces hold copies of the package (its launch files among them): left inside the
  # package's directory, roslaunch would find two of each by name afterwards. The logs stay.
  rm -rf "$ws" "$user_ws" "$base/moved"
  echo "install test: $((SECONDS - started)) s (logs in ${base#"$root/"}/)"
  echo "$passed passed, $failed failed"
  exit $((failed > 0 ? 1 : 0))
}

# Nothing from the caller's ROS environment (a sourced devel space, a running master) may leak in.
unset ROS_PACKAGE_PATH CMAKE_PREFIX_PATH PYTHONPATH LD_LIBRARY_PATH PKG_CONFIG_PATH ROS_MASTER_URI ROS_IP \
  ROS_HOSTNAME ROS_NAMESPACE ROS_ROOT ROS_ETC_DIR ROS_DISTRO ROS_VERSION ROS_PYTHON_VERSION ROSLISP_PACKAGE_DIRECTORIES \
  CATKIN_SHELL SPATIAL_DYNAMICS_SIMD
rm -rf "$base"
mkdir -p "$ws/src/spatial_dynamics" "$user_ws/src" "$base/moved" "$base/ros_home"
export ROS_HOME="$base/ros_home" ROS_LOG_DIR="$base/ros_home/log"

# --- 1. build and install -------------------------------------------------------------------
if git -C "$root" rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  git -C "$root" ls-files -z --cached --others --exclude-standard |
    tar -C "$root" --null --ignore-failed-read -T - -cf - 2>/dev/null | tar -C "$ws/src/spatial_dynamics" -xf -
else
  tar -C "$root" --exclude='./build*' --exclude='./devel' --exclude='./install' -cf - . |
    tar -C "$ws/src/spatial_dynamics" -xf -
fi
cp -r "$root/test/downstream/dynamics_user" "$user_ws/src/"

catkin_args=(-DPYTHON_EXECUTABLE=/usr/bin/python3 -DCMAKE_BUILD_TYPE=Release -DCATKIN_ENABLE_TESTING=OFF)
if command -v ccache >/dev/null 2>&1; then
  catkin_args+=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
fi
# catkin_make WORKSPACE LOG [ARGS...], with ccache hashing paths relative to the workspace.
catkin_build() {
  local dir=$1 log=$2
  shift 2
  (cd "$dir" && CCACHE_BASEDIR="$dir" CCACHE_NOHASHDIR=1 timeout "$build_timeout" \
     catkin_make -j"$(nproc)" "$@" "${catkin_args[@]}") >"$log" 2>&1
}

echo "building and installing the package in ${ws#"$root/"}/ ..."
t0=$SECONDS
if catkin_build "$ws" "$base/build.log" install -DSPATIAL_DYNAMICS_BENCHMARK=OFF; then
  pass "catkin_make install of spatial_dynamics ($((SECONDS - t0)) s)"
else
  fail_check "catkin_make install of spatial_dynamics" "$base/build.log"
  finish
fi

# --- 2. only the install space is left --------------------------------------------------------
mv "$ws/src" "$ws/build" "$ws/devel" "$base/moved/"
set +u  # the ROS environment scripts read unset variables
# shellcheck disable=SC1091
source "$install/setup.bash"
set -u
export ROS_MASTER_URI="http://localhost:$port" ROS_HOSTNAME=localhost

# --- 3. the install space's files, print_gravity_torques --------------------------------------
missing=()
for f in lib/libspatial_dynamics.so lib/libspatial_dynamics_portable.so lib/libspatial_dynamics_avx2_fma.so \
         lib/libspatial_dynamics_urdf.so lib/libspatial_dynamics_ros.so \
         lib/spatial_dynamics/dynamics_node lib/spatial_dynamics/print_gravity_torques \
         lib/spatial_dynamics/demo_joint_state_source.py \
         include/spatial_dynamics/algorithms.hpp include/spatial_dynamics/urdf/model_builder.hpp \
         include/spatial_dynamics/ros/dynamics_node.hpp include/spatial_dynamics/InverseDynamics.h \
         share/spatial_dynamics/package.xml share/spatial_dynamics/cmake/spatial_dynamicsConfig.cmake \
         share/spatial_dynamics/urdf/panda.urdf share/spatial_dynamics/launch/dynamics.launch \
         share/spatial_dynamics/launch/demo.launch share/spatial_dynamics/srv/InverseDynamics.srv \
         lib/python3/dist-packages/spatial_dynamics/client.py \
         lib/python3/dist-packages/spatial_dynamics/srv/_InverseDynamics.py; do
  [ -e "$install/$f" ] || missing+=("$f")
done
unwanted=$(find "$install" -name '*synthetic*' | sed "s|^$install/||")
# Text files naming the source tree or the moved workspace (binaries keep __FILE__ strings of
# log macros, which nothing opens).
stale=$(grep -rIlF -e "$ws/src" -e "$ws/build" -e "$ws/devel" -e "$root/src" -e "$root/urdf" -e "$root/launch" \
          "$install" 2>/dev/null | sed "s|^$install/||")
if [ ${#missing[@]} -eq 0 ] && [ -z "$unwanted" ] && [ -z "$stale" ]; then
  pass "the install space has the libraries, headers, programs, URDFs, launch files and Python modules, no test helper, no source paths"
else
  [ ${#missing[@]} -eq 0 ] || echo "  missing: ${missing[*]}"
  [ -z "$unwanted" ] || echo "  installed though only for tests: $unwanted"
  [ -z "$stale" ] || echo "  naming the source tree or the build: $stale"
  fail_check "the install space's files"
fi

log="$base/print_gravity_torques.log"
if timeout 60 rosrun spatial_dynamics print_gravity_torques >"$log" 2>&1 &&
   head -n 1 "$log" | grep -qxF "model: $install/share/spatial_dynamics/urdf/panda.urdf" &&
   grep -q 'panda_joint7' "$log"; then
  pass "rosrun spatial_dynamics print_gravity_torques: $(head -n 1 "$log")"
else
  fail_check "rosrun spatial_dynamics print_gravity_torques (its default URDF from the share directory)" "$log"
fi
log="$base/print_gravity_torques_unfound.log"
if ! env -u ROS_PACKAGE_PATH timeout 60 "$install/lib/spatial_dynamics/print_gravity_torques" >"$log" 2>&1 &&
   grep -q 'urdf/panda.urdf of the package spatial_dynamics' "$log" && grep -q 'ROS_PACKAGE_PATH' "$log"; then
  pass "print_gravity_torques without ROS_PACKAGE_PATH fails and names what is missing"
else
  fail_check "print_gravity_torques without ROS_PACKAGE_PATH (a clear error)" "$log"
fi

# --- 4. the downstream package, built against the install space --------------------------------
echo "building test/downstream/dynamics_user in ${user_ws#"$root/"}/ ..."
t0=$SECONDS
user_lib="$user_ws/devel/lib/dynamics_user"
if catkin_build "$user_ws" "$base/user_build.log"; then
  found=$(sed -n 's/^spatial_dynamics_DIR:PATH=//p' "$user_ws/build/CMakeCache.txt")
  linked=$(ldd "$user_lib/check_inverse_dynamics" | sed -n 's/^\s*libspatial_dynamics\.so => \(\S*\).*/\1/p')
  if [ "$found" = "$install/share/spatial_dynamics/cmake" ] && [ "$linked" = "$install/lib/libspatial_dynamics.so" ]; then
    pass "dynamics_user builds against the install space ($((SECONDS - t0)) s; spatial_dynamics_DIR and libspatial_dynamics.so from install/)"
  else
    echo "  spatial_dynamics_DIR = $found; libspatial_dynamics.so => $linked"
    fail_check "dynamics_user is built against the install space"
  fi
else
  fail_check "catkin_make of dynamics_user against the install space" "$base/user_build.log"
fi

# --- 5. the installed node, and the downstream checks against it ----------------------------
launch_pid=
stop_node() {
  [ -n "$launch_pid" ] || return 0
  kill -INT -- "-$launch_pid" 2>/dev/null || true
  for _ in $(seq 100); do kill -0 "$launch_pid" 2>/dev/null || break; sleep 0.1; done
  kill -KILL -- "-$launch_pid" 2>/dev/null || true
  wait "$launch_pid" 2>/dev/null || true
  launch_pid=
}
trap stop_node EXIT

serving=false
log="$base/roslaunch.log"
if timeout 10 rosnode list >/dev/null 2>&1; then
  fail_check "roslaunch spatial_dynamics dynamics.launch: a ROS master already runs on port $port (set SPATIAL_DYNAMICS_INSTALL_TEST_PORT)"
else
  # In a process group of its own (setsid), so that stop_node ends the master and the node with it.
  setsid roslaunch -p "$port" spatial_dynamics dynamics.launch >"$log" 2>&1 &
  launch_pid=$!
  for _ in $(seq 300); do  # up to 60 s
    kill -0 "$launch_pid" 2>/dev/null || break
    timeout 10 rosservice list 2>/dev/null | grep -qx /dynamics/inverse_dynamics && { serving=true; break; }
    sleep 0.2
  done
  if $serving; then
    pass "roslaunch spatial_dynamics dynamics.launch serves /dynamics/inverse_dynamics (master on port $port)"
  else
    fail_check "roslaunch spatial_dynamics dynamics.launch (no /dynamics/inverse_dynamics within 60 s)" "$log"
  fi
fi

# run_downstream WHAT LOG COMMAND...: the command's lines, indented; passes when it exits with 0.
run_downstream() {
  local what=$1 log=$2
  shift 2
  if ! $serving || [ ! -x "$1" ]; then
    fail_check "$what (not run: no node or no program)"
    return
  fi
  timeout 120 "$@" >"$log" 2>&1
  local rc=$?
  grep -E '^(PASS|FAIL|model|modules)' "$log" | sed 's/^/  /'
  if [ $rc -eq 0 ] && grep -q '^PASS' "$log" && ! grep -q '^FAIL' "$log"; then
    pass "$what"
  else
    fail_check "$what (exit status $rc)" "$log"
  fi
}
run_downstream "dynamics_user C++ check: sd::rnea on the installed Panda, and ~inverse_dynamics = sd::rnea" \
  "$base/check_cpp.log" "$user_lib/check_inverse_dynamics" /dynamics
run_downstream "dynamics_user Python check: spatial_dynamics.srv and spatial_dynamics.client from the install space" \
  "$base/check_python.log" /usr/bin/python3 "$user_ws/src/dynamics_user/scripts/check_inverse_dynamics.py" \
  --node /dynamics --prefix "$install"

stop_node
finish
