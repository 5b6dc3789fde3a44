# shellcheck shell=bash
# Sourced by the test scripts (after `cd` to the repository root): the system interpreter first on
# PATH (Debian's catkin needs its catkin_pkg), and fail(), which ends a run with CI's count line.
export PATH="/usr/bin:$PATH"

fail() {
  echo "error: $1" >&2
  echo "0 passed, 1 failed"
  exit 1
}
