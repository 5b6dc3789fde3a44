#!/usr/bin/env bash
# The speed-against-error benchmark: installs what it needs beyond the build and tests (DART,
# MuJoCo, matplotlib; KDL comes with the tests' dependencies), builds it and runs it.
# Arguments go to the benchmark; e.g. --quick, --model PATH, --default-build. Writes results.csv,
# results.md and benchmark.png into the --out directory: by default doc/benchmark/ (the committed
# results), and build/benchmark_quick/ for --quick, whose short timings must not replace them.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_dependencies.sh

packages=(libdart-dev libdart-utils-urdf-dev libmujoco-dev python3-matplotlib)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  as_root=()
  [ "$(id -u)" -eq 0 ] || as_root=(sudo)
  echo "Installing: ${missing[*]}"
  "${as_root[@]}" apt-get update
  DEBIAN_FRONTEND=noninteractive "${as_root[@]}" apt-get install -y --no-install-recommends "${missing[@]}"
fi

bash scripts/build.sh benchmark
args=("$@")
case " $* " in
  *" --out "*) ;;
  *" --quick "*) args+=(--out build/benchmark_quick) ;;
  *) args+=(--out doc/benchmark) ;;
esac
./build/devel/lib/spatial_dynamics/benchmark "${args[@]}"
