#!/usr/bin/env bash
# The long-function check's self-test: a planted plugin.cpp of 170 lines holding a function of 85
# must be caught, both as a long function and as a long adapter, naming the file and the function.
set -eu
src=$1; work=$2
rm -rf "$work"; mkdir -p "$work/planted"
f=$work/planted/plugin.cpp
{
  echo "void planted_long_function() {"
  for i in $(seq 1 83); do echo "  (void)$i;"; done
  echo "}"
  for i in $(seq 1 85); do echo "// filler $i"; done
} > "$f"
out=$(cd "$src" && LONG_FUNCTIONS_EXTRA=$f scripts/long-functions --check 2>&1) && { echo "FAIL: the check passed a planted long function:"; echo "$out"; exit 1; }
echo "$out" | grep -q "^85 $f planted_long_function$" || { echo "FAIL: the long function not named:"; echo "$out"; exit 1; }
echo "$out" | grep -q "^170 $f (plugin.cpp)$" || { echo "FAIL: the long plugin.cpp not named:"; echo "$out"; exit 1; }
echo "caught: $(echo "$out" | tail -n +2 | tr '\n' ';')"
