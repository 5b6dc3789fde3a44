#!/usr/bin/env bash
# Installs what the libFuzzer targets (fuzz/, scripts/run_fuzzers.sh) need on Debian 12: the
# package's own dependencies plus clang 14 and its runtime libraries (libFuzzer, the sanitizers).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_dependencies.sh clang-14 libclang-rt-14-dev
