#!/usr/bin/env bash
# data/planned_lines/ must be what brickyard-plan computes today for each track (the header
# comment names the input path and is not compared).
#   planned_lines_current.sh BRICKYARD_PLAN SOURCE_DIR SCRATCH
set -u
plan=$1; src=$2; scratch=$3
mkdir -p "$scratch"
bad=0
for f in "$src"/data/planned_lines/*.csv; do
  t=$(basename "$f" .csv)
  "$plan" line --track "$src/data/tracks/$t.csv" --out "$scratch/$t.csv" > /dev/null || { echo "FAIL: brickyard-plan line $t"; exit 1; }
  if ! diff -q <(grep -v '^# minimum' "$f") <(grep -v '^# minimum' "$scratch/$t.csv") > /dev/null; then
    echo "FAIL: data/planned_lines/$t.csv differs from brickyard-plan's line (regenerate it: docs/control.md)"; bad=1
  fi
done
[ $bad -eq 0 ] && echo "planned lines: current"
exit $bad
