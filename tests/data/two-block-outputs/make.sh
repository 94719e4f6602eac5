#!/usr/bin/env bash
# Records the files of every case in cases.txt with the adjoin binary given (built from the
# commit named in README.md here), keeping every 10th row of the CSV files (and the header):
#     tests/data/two-block-outputs/make.sh build/adjoin
set -euo pipefail
adjoin=$(realpath "$1")
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../../.." && pwd)
cd "$root"
grep -v '^#' "$here/cases.txt" | while read -r name scene args; do
  [ -n "$name" ] || continue
  out=$(mktemp -d)
  # shellcheck disable=SC2086
  rm -rf "${here:?}/$name"; mkdir -p "$here/$name"
  # The terminal report too, with the temporary folder written as OUT.
  "$adjoin" run "$scene" $args --out "$out/run" 2>/dev/null | sed "s|$out/run|OUT|g" > "$here/$name/stdout.txt"
  for f in "$out"/run/*; do
    case "$f" in
      *.csv) awk 'NR == 1 || (NR - 2) % 10 == 0' "$f" > "$here/$name/$(basename "$f")" ;;
      *) cp "$f" "$here/$name/" ;;
    esac
  done
  rm -rf "$out"
done
