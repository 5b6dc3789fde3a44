#!/usr/bin/env bash
# Builds the package with sanitizers into a build directory of its own (for `unit`, the unit tests
# and the libraries they link; otherwise the libraries, the node, the tools and every test) and
# runs the tests there; the last line is "N passed, N failed".
#   run_sanitized_tests.sh address [all|unit|rostest]
#       AddressSanitizer + LeakSanitizer + UndefinedBehaviorSanitizer, in build/asan/ (default: all)
#   run_sanitized_tests.sh thread [all|unit|rostest]
#       ThreadSanitizer, in build/tsan/ (default: all)
# The build is optimised (-O1 for address, -Og for its unit tests alone, -O2 for thread) with line tables (-g1) and assertions on (Eigen's
# index and size checks, and _GLIBCXX_ASSERTIONS for the standard containers). Every sanitizer writes its reports into
# BUILD_DIR/sanitizer_reports/, and each report counts as a failed test (scripts/test_suite.sh):
# that is how a finding in the node, whose exit code rostest ignores, fails the run.
# Suppressions (only for code that is not ours, each one explained) are in test/sanitizers/.
set -uo pipefail
cd "$(dirname "$0")/.." || exit 1
# shellcheck source=scripts/test_common.sh
source scripts/test_common.sh

kind="${1:-}"
selection="${2:-all}"
# -O1 keeps AddressSanitizer's reports exact; ThreadSanitizer costs 5–15× and gets -O2, so that
# the node under test still keeps up with the concurrency test's 500 Hz joint-state stream. The
# unit tests alone have no such deadline and take -Og, which compiles in about 40 % less time than -O1
# (test_algorithms.cpp: 49 s instead of 86 s) and keeps every check.
case "$kind" in
  address) sanitizers=address,undefined; build_dir=build/asan; optimisation=-O1 ;;
  thread) sanitizers=thread; build_dir=build/tsan; optimisation=-O2 ;;
  *) fail "usage: run_sanitized_tests.sh address|thread [all|unit|rostest]" ;;
esac

# The unit tests need neither the node nor its integration tests: only they are built then.
case "$selection" in
  unit) targets=(unit_tests); [ "$kind" = address ] && optimisation=-Og ;;
  *) targets=(all tests) ;;
esac

bash scripts/install_dependencies.sh || fail "installing dependencies failed"
bash scripts/build.sh -B "$build_dir" -DSPATIAL_DYNAMICS_SANITIZE="$sanitizers" -DSPATIAL_DYNAMICS_BENCHMARK=OFF \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=$optimisation -g1" "${targets[@]}" ||
  fail "the $kind-sanitized build failed"

reports="$PWD/$build_dir/sanitizer_reports"
suppressions="$PWD/test/sanitizers"
rm -rf "$reports"
mkdir -p "$reports"
# log_path: one file per process that found something (tests and the node alike).
export LSAN_OPTIONS="suppressions=$suppressions/lsan.supp:print_suppressions=0"
export ASAN_OPTIONS="log_path=$reports/asan:detect_leaks=1:detect_stack_use_after_return=1:check_initialization_order=1:strict_init_order=1:detect_invalid_pointer_pairs=0"
export UBSAN_OPTIONS="log_path=$reports/ubsan:print_stacktrace=1:halt_on_error=1"
export TSAN_OPTIONS="log_path=$reports/tsan:suppressions=$suppressions/tsan.supp:print_suppressions=0"
echo "running the $selection tests with -fsanitize=$sanitizers (reports: $build_dir/sanitizer_reports/)"
bash scripts/test_suite.sh "$build_dir" "$selection"
