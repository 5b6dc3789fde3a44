#!/usr/bin/env bash
# Builds the libFuzzer targets of fuzz/ with clang, AddressSanitizer and UndefinedBehaviorSanitizer
# into build/fuzz/, then either fuzzes or replays the corpora.
#   run_fuzzers.sh [SECONDS] [TARGET ...]
#       fuzz each target for SECONDS (default 600), one after another on one core (nice -n 19),
#       starting from its corpus, its seeds and (URDF target) the robots in urdf/; then
#       merge everything into a minimised fuzz/<target>/corpus/ (libFuzzer -merge=1). Crashing
#       inputs go to build/fuzz/artifacts/. Prints executions, corpus size and findings per target.
#   run_fuzzers.sh replay [TARGET ...]
#       run each target once over every file of its corpus and seeds, without mutating (what CI
#       does); the last line is "N passed, N failed", one test per target.
# TARGET: urdf_builder, scene_reduction, service_handlers (default: all three). Needs clang-14 and libclang-rt-14-dev
# (scripts/install_fuzzing_dependencies.sh installs them).
set -uo pipefail
cd "$(dirname "$0")/.." || exit 1
# shellcheck source=scripts/test_common.sh
source scripts/test_common.sh

mode=fuzz
seconds=600
if [ "${1:-}" = replay ]; then
  mode=replay
  shift
elif [[ "${1:-}" =~ ^[0-9]+$ ]]; then
  seconds="$1"
  shift
fi
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(urdf_builder scene_reduction service_handlers external_torques payload_identification)
for t in "${targets[@]}"; do
  [ -f "fuzz/$t/fuzz_$t.cpp" ] || fail "unknown fuzz target '$t' (urdf_builder, scene_reduction, service_handlers, external_torques or payload_identification)"
done

bash scripts/install_fuzzing_dependencies.sh || fail "installing the fuzzing dependencies failed"
build_dir=build/fuzz
bash scripts/build.sh -B "$build_dir" -DCMAKE_CXX_COMPILER=clang++-14 -DSPATIAL_DYNAMICS_FUZZ=ON -DSPATIAL_DYNAMICS_BENCHMARK=OFF \
  -DSPATIAL_DYNAMICS_SANITIZE=address,undefined -DCATKIN_ENABLE_TESTING=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1" "${targets[@]/#/fuzz_}" || fail "building the fuzz targets failed"

export ASAN_OPTIONS="detect_leaks=1:allocator_may_return_null=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
robots_dir="${SD_ROBOTS_DIR:-urdf}"

# Seed files of a target: its seeds/ directory and, for the URDF target, the shared robots.
seed_files() {
  find "fuzz/$1/seeds" -type f 2>/dev/null
  if [ "$1" = urdf_builder ]; then find "$robots_dir" -name '*.urdf' 2>/dev/null; fi
}

passed=0
failed=0
for t in "${targets[@]}"; do
  binary="$build_dir/fuzz/fuzz_$t"
  corpus="fuzz/$t/corpus"
  mkdir -p "$corpus" "$build_dir/artifacts" "$build_dir/logs"
  # Small inputs reach every code path and run fast: the URDF target stays below 8 KiB (the shared
  # robots are replayed whole), the scene target reads a few hundred bytes at most.
  case "$t" in
    urdf_builder) options=(-max_len=8192 "-dict=fuzz/$t/$t.dict") ;;
    service_handlers) options=(-max_len=4096) ;;  # arrays up to thousands of entries
    payload_identification) options=(-max_len=4096) ;;  # tens of points of several arrays
    *) options=(-max_len=512) ;;
  esac
  log="$build_dir/logs/$t.$mode.log"

  if [ "$mode" = replay ]; then
    mapfile -t files < <({ find "$corpus" -type f; seed_files "$t"; } | sort)
    echo "== $t: replaying ${#files[@]} inputs"
    if "$binary" -runs=1 -timeout=30 "${files[@]}" >"$log" 2>&1; then
      passed=$((passed + 1))
    else
      failed=$((failed + 1))
      grep -E 'FINDING|ERROR|SUMMARY|Running:' "$log" | tail -n 20
      echo "$t: replay failed (log: $log)" >&2
    fi
    continue
  fi

  # Fuzz: new inputs go to a scratch corpus; seeds are copied so that nothing outside build/fuzz/ is written.
  scratch="$build_dir/campaign/$t"
  seeds="$build_dir/seeds/$t"
  rm -rf "$scratch" "$seeds"
  mkdir -p "$scratch" "$seeds"
  seed_files "$t" | while read -r f; do cp "$f" "$seeds/"; done
  echo "== $t: fuzzing for $seconds s (log: $log)"
  before=$(find "$build_dir/artifacts" -name "$t-*" -type f | wc -l)
  nice -n 19 "$binary" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
    -artifact_prefix="$build_dir/artifacts/$t-" "${options[@]}" "$scratch" "$corpus" "$seeds" >"$log" 2>&1
  status=$?
  crashes=$(( $(find "$build_dir/artifacts" -name "$t-*" -type f | wc -l) - before ))
  executions=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -n 1)
  elapsed=$(sed -n 's/^Done [0-9]* runs in \([0-9]*\) second.*/\1/p' "$log" | tail -n 1)
  # Minimise: the new corpus keeps the fewest inputs that cover every edge the old one, the scratch and
  # the seeds cover (-use_counters=0: edges, not hit counts, so that it stays a few hundred files).
  merged="$build_dir/merged/$t"
  rm -rf "$merged"
  mkdir -p "$merged"
  if nice -n 19 "$binary" -merge=1 -use_counters=0 -timeout=10 "${options[0]}" "$merged" "$corpus" "$scratch" "$seeds" \
    >"$build_dir/logs/$t.merge.log" 2>&1; then
    rm -rf "$corpus"
    mv "$merged" "$corpus"
  else
    echo "$t: merging the corpus failed (log: $build_dir/logs/$t.merge.log); the corpus is unchanged" >&2
  fi
  size=$(find "$corpus" -type f | wc -l)
  echo "$t: ${executions:-?} executions in ${elapsed:-?} s, exit status $status, $crashes crashing input(s), corpus $size files"
  if [ "$status" -eq 0 ] && [ "$crashes" -eq 0 ]; then
    passed=$((passed + 1))
  else
    failed=$((failed + 1))
    grep -E 'FINDING|ERROR|SUMMARY' "$log" | head -n 20
  fi
done
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
