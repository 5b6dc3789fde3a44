#!/usr/bin/env bash
# Installs what is needed, builds everything, runs every test (gtest unit tests and rostest
# integration tests), then installs the package into a scratch workspace and checks a downstream
# package against it (scripts/test_install.sh); ends with the line "N passed, N failed", the sum of
# both. Fails when any test or check fails or when fewer tests ran than test/minimum_test_count
# says (a silently skipped test target).
set -uo pipefail
cd "$(dirname "$0")/.." || exit 1
# shellcheck source=scripts/test_common.sh
source scripts/test_common.sh

bash scripts/install_dependencies.sh || fail "installing dependencies failed"
bash scripts/build.sh all tests || fail "the build failed"

total_passed=0
total_failed=0
status=0
# Runs one part, shows its output, and adds the counts of its last line to the totals (a part that
# ends without its count line, or fails without counting a failure, counts as one failure).
part() {
  local log rc last
  log=$(mktemp)
  "$@" | tee "$log"
  rc=${PIPESTATUS[0]}
  last=$(tail -n 1 "$log")
  rm -f "$log"
  if [[ "$last" =~ ^([0-9]+)\ passed,\ ([0-9]+)\ failed$ ]]; then
    total_passed=$((total_passed + BASH_REMATCH[1]))
    total_failed=$((total_failed + BASH_REMATCH[2]))
    [ "$rc" -eq 0 ] || [ "${BASH_REMATCH[2]}" -gt 0 ] || total_failed=$((total_failed + 1))
  else
    total_failed=$((total_failed + 1))
  fi
  [ "$rc" -eq 0 ] || status=1
}

part bash scripts/test_suite.sh build all
echo "=== the installed package, used from a downstream package (scripts/test_install.sh)"
part bash scripts/test_install.sh
echo "$total_passed passed, $total_failed failed"
[ "$status" -eq 0 ] && [ "$total_failed" -eq 0 ]
