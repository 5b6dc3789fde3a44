#!/usr/bin/env bash
# Installs what is needed, builds everything, runs every test (gtest unit tests and rostest
# integration tests) and ends with the line "N passed, N failed". Fails when any test fails or
# when fewer tests ran than test/minimum_test_count says (a silently skipped test target).
set -uo pipefail
cd "$(dirname "$0")/.." || exit 1
# shellcheck source=scripts/test_common.sh
source scripts/test_common.sh

bash scripts/install_dependencies.sh || fail "installing dependencies failed"
bash scripts/build.sh all tests || fail "the build failed"
bash scripts/test_suite.sh build all
