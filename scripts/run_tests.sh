#!/usr/bin/env bash
# Installs what is needed, builds everything, runs every test (gtest unit tests and rostest
# integration tests) and ends with the line "N passed, N failed". Fails when any test fails or
# when fewer tests ran than test/minimum_test_count says (a silently skipped test target).
set -uo pipefail
cd "$(dirname "$0")/.."
export PATH="/usr/bin:$PATH"

fail() {
  echo "error: $1" >&2
  echo "0 passed, 1 failed"
  exit 1
}

bash scripts/install_dependencies.sh || fail "installing dependencies failed"
bash scripts/build.sh all tests || fail "the build failed"
rm -rf build/test_results
set +u  # the ROS environment scripts read unset variables
# shellcheck disable=SC1091
source build/devel/setup.bash
set -u
make -C build --no-print-directory run_tests >build/run_tests.log 2>&1
status=$?
grep -E '^\[ *(FAILED|PASSED) *\]|^\[kdl_oracle\]|^\[.*\] (ABA|ID)|Failure|Expected|actual' build/run_tests.log || true
[ $status -eq 0 ] || fail "make run_tests failed (see build/run_tests.log)"

read -r passed failed skipped < <(/usr/bin/python3 scripts/count_test_results.py build/test_results) ||
  fail "could not read the test results"
tests=$((passed + failed + skipped))
minimum=$(cat test/minimum_test_count)
if [ "$tests" -lt "$minimum" ]; then
  echo "error: only $tests tests ran; at least $minimum are expected (is a test target skipped?)" >&2
  failed=$((failed + minimum - tests))
fi
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
