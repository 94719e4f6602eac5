#!/usr/bin/env bash
# Instruction counts (valgrind --tool=callgrind: repeatable whatever the machine's load) of the
# runs issue 24 sets targets for. Builds nothing: give it a build directory holding `adjoin`.
#
#     bench/instructions.sh build [OUT_DIR]      # from the repository root; OUT_DIR default /tmp/adjoin-instructions
#
# Per step = (the whole run's instructions - a one-step run's) / (steps - 1): the one-step run
# (solver.t_end = h) holds the process start, the scene's set-up and the outputs' writing once.
#
# Part 1, the one-damper pair: frames A and B (5 and 3 storeys) joined at floor 3 by a friction
# damper, El Centro 1940 NS, dt = 0.001 s, 31,180 steps (bench/instructions/one-damper-elcentro.toml)
#   solve    : the solve with its observers (peaks, channels, energy balance, summary.json):
#              --set output.timeseries=false --set solver.error_estimate=false
#   all on   : as the scene says: the time series every 10 steps and the error estimate's
#              companion run at 2h (another half run)
# and, for comparison with earlier figures, examples/buildings/two-frames-one-damper.toml
# (the same pair under Newhall, h = 0.002 s, 25,000 steps) in both readings.
# Part 2, one run of the paper's strong scene, implicit, soe history, 8,000 steps:
#   --set solver.scheme=implicit --set solver.history=soe --set output.timeseries=false
#   --set solver.error_estimate=false   (total instructions: the target is on the whole process)
set -euo pipefail

build=${1:?usage: bench/instructions.sh BUILD_DIR [OUT_DIR]}
out=${2:-/tmp/adjoin-instructions}
adjoin="$build/adjoin"
[[ -x "$adjoin" ]] || { echo "error: $adjoin is not an executable (build the adjoin_cli target)" >&2; exit 2; }
command -v valgrind >/dev/null || { echo "error: valgrind is not installed" >&2; exit 2; }
mkdir -p "$out"

# count NAME ARGS...: runs `adjoin run ARGS` under callgrind, prints nothing, echoes the total.
# (--allow-long: under callgrind on a loaded machine the run watch's estimate from the first step
# can pass its two-hour limit and refuse the run.)
count() {
  local name=$1; shift
  valgrind --tool=callgrind --callgrind-out-file="$out/$name.cg" "$adjoin" run "$@" --allow-long --out "$out/$name" \
    >"$out/$name.log" 2>&1 || { echo "error: adjoin run $* failed (see $out/$name.log)" >&2; exit 3; }
  awk '/^(summary|totals):/ {print $2; exit}' "$out/$name.cg"
}

# report LABEL STEPS H SCENE ARGS...: the whole run and the one-step run, per step and total.
report() {
  local label=$1 steps=$2 h=$3 scene=$4; shift 4
  local tag=${label//[^A-Za-z0-9]/_}
  local whole one
  whole=$(count "$tag" "$scene" "$@")
  one=$(count "$tag-1" "$scene" "$@" --set solver.t_end="$h")
  awk -v l="$label" -v w="$whole" -v o="$one" -v n="$steps" \
    'BEGIN { printf "%-44s %8.1fM total  %8.1fM one step  %7.2fk a step\n", l, w / 1e6, o / 1e6, (w - o) / (n - 1) / 1e3 }'
}

solve=(--set output.timeseries=false --set solver.error_estimate=false)
pair=bench/instructions/one-damper-elcentro.toml
example=examples/buildings/two-frames-one-damper.toml
strong=records/scenes/paper-strong.toml

echo "instructions (callgrind), $adjoin"
report "part 1: one-damper pair, El Centro, solve" 31180 0.001 "$pair" "${solve[@]}"
report "part 1: one-damper pair, El Centro, all on" 31180 0.001 "$pair"
report "two-frames-one-damper example, solve" 25000 0.002 "$example" "${solve[@]}"
report "two-frames-one-damper example, all on" 25000 0.002 "$example"
report "part 2: strong scene, implicit, soe" 8000 0.002 "$strong" \
  --set solver.scheme=implicit --set solver.history=soe "${solve[@]}"
