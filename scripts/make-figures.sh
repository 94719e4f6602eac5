#!/usr/bin/env bash
# Remakes the documentation's figures, docs/figures/paper-strong-*.png, with the project itself:
# solves the seed paper's strong-excitation scene (with its energy history) and draws the
# figures with `adjoin plot run`.
#
#     scripts/make-figures.sh [BUILD_DIR]     (default build/; configured and built if needed)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release
fi
cmake --build "$build" -j2 --target adjoin_cli

out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
"$build/adjoin" run "$root/records/scenes/paper-strong.toml" --out "$out" \
  --set output.timeseries=true --set output.energy_history=true --quiet
mkdir -p "$root/docs/figures"
"$build/adjoin" plot run "$out" --out "$root/docs/figures/paper-strong-" --size 900x600
