#!/usr/bin/env bash
# Runs the tests of an already built build directory and ends with the line "N passed, N failed".
#   test_suite.sh BUILD_DIR [all|unit|rostest]
#     all      every gtest unit test and rostest integration test (make run_tests); at least
#              test/minimum_test_count must run
#     unit     the gtest unit tests only; at least test/minimum_unit_test_count must run
#     rostest  the rostest integration tests only; at least minimum_test_count − minimum_unit_test_count
#              − minimum_python_test_count
#   (the Python bindings' nose tests run with `all`; a build without the bindings, as the sanitizer
#   builds are, owes test/minimum_python_test_count fewer)
# Extra catkin test targets to run as well can follow (e.g. a single rostest's target).
# Fails when any test fails, when fewer tests ran than the minimum (a test target that the build
# silently skipped cannot shrink the suite unnoticed), or when a sanitizer wrote a report into
# BUILD_DIR/sanitizer_reports/ (scripts/run_sanitized_tests.sh points the sanitizers there, so
# findings in the node, which rostest does not judge by exit code, count too: one failure each).
# Shared by scripts/run_tests.sh and scripts/run_sanitized_tests.sh.
set -uo pipefail
cd "$(dirname "$0")/.." || exit 1
# shellcheck source=scripts/test_common.sh
source scripts/test_common.sh

build_dir="${1:?usage: test_suite.sh BUILD_DIR [all|unit|rostest] [catkin test targets ...]}"
selection="${2:-all}"
shift $(( $# < 2 ? $# : 2 ))
minimum_all=$(cat test/minimum_test_count)
minimum_unit=$(cat test/minimum_unit_test_count)
minimum_python=$(cat test/minimum_python_test_count)
case "$selection" in
  all) targets=(run_tests); minimum=$minimum_all
       if grep -q '^SPATIAL_DYNAMICS_PYTHON_BINDINGS:BOOL=OFF' "$build_dir/CMakeCache.txt" 2>/dev/null; then
         minimum=$((minimum_all - minimum_python))
       fi ;;
  unit) targets=(run_tests_spatial_dynamics_gtest); minimum=$minimum_unit ;;
  rostest) targets=(run_tests_spatial_dynamics_rostest); minimum=$((minimum_all - minimum_unit - minimum_python)) ;;
  *) fail "unknown test selection '$selection' (all, unit or rostest)" ;;
esac
targets+=("$@")
[ -f "$build_dir/devel/setup.bash" ] || fail "$build_dir/ is not built"

rm -rf "$build_dir/test_results"
set +u  # the ROS environment scripts read unset variables
# shellcheck disable=SC1091
source "$build_dir/devel/setup.bash"
set -u
make -C "$build_dir" --no-print-directory "${targets[@]}" >"$build_dir/run_tests.log" 2>&1
status=$?
grep -E '^\[ *(FAILED|PASSED) *\]|^\[bindings\]|^\[kdl_oracle\]|^\[.*\] (ABA|ID)|^\[concurrency\]|Failure|Expected|actual' \
  "$build_dir/run_tests.log" || true
[ $status -eq 0 ] || fail "make ${targets[*]} failed (see $build_dir/run_tests.log)"

read -r passed failed skipped < <(/usr/bin/python3 scripts/count_test_results.py "$build_dir/test_results") ||
  fail "could not read the test results"
tests=$((passed + failed + skipped))
if [ "$tests" -lt "$minimum" ]; then
  echo "error: only $tests tests ran; at least $minimum are expected (is a test target skipped?)" >&2
  failed=$((failed + minimum - tests))
fi

reports=()
if [ -d "$build_dir/sanitizer_reports" ]; then
  mapfile -t reports < <(find "$build_dir/sanitizer_reports" -type f | sort)
fi
for report in "${reports[@]}"; do
  echo "sanitizer report $report:" >&2
  head -n 60 "$report" >&2
done
if [ ${#reports[@]} -gt 0 ]; then
  echo "error: ${#reports[@]} sanitizer report(s) in $build_dir/sanitizer_reports/" >&2
  failed=$((failed + ${#reports[@]}))
fi
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
