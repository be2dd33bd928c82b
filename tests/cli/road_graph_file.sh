#!/usr/bin/env bash
# brickyard-plan graph writes the road graph planning.road_graph builds at start; the planner
# loads it (graph_file) and drives the pylon test as it does with its own; a damaged file, or one
# built for other parameters, or a FIFO, stops the run in configure with exit 2 naming the file.
set -u
plan=$1; by=$2; graph=$3; data=$4; domain=$5; out=$6
rm -rf "$out"; mkdir -p "$out"
g="$out/ims.byrg"
"$plan" graph --track "$data/tracks/IMS.csv" --raceline "$data/racelines/IMS.csv" --edge-margin 3.5 --out "$g" \
  || { echo "FAIL: brickyard-plan graph exit $?"; exit 1; }
"$by" run "$graph" --domain "$domain" --out "$out/run" --set planner.graph_file="$g" > "$out/run.log" 2>&1
rc=$?; [ $rc -eq 0 ] || { cat "$out/run.log"; echo "FAIL: run with the graph file: exit $rc"; exit 1; }
grep -q "road graph loaded from $g" "$out/run.log" || { cat "$out/run.log"; echo "FAIL: the file was not used"; exit 1; }
expect_bad() {  # file, pattern
  timeout 20 "$by" run "$graph" --domain "$domain" --quiet --out "$out/bad" --set planner.graph_file="$1" > "$out/bad.log" 2>&1
  rc=$?
  [ $rc -eq 2 ] || { cat "$out/bad.log"; echo "FAIL: $1: exit $rc, expected 2"; exit 1; }
  grep -q -- "$2" "$out/bad.log" || { cat "$out/bad.log"; echo "FAIL: $1: message lacks '$2'"; exit 1; }
}
head -c 100000 "$g" > "$out/cut.byrg"
expect_bad "$out/cut.byrg" "cut.byrg: not a usable road graph (its digest does not match its bytes: damaged or cut short"
"$plan" graph --track "$data/tracks/IMS.csv" --raceline "$data/racelines/IMS.csv" --edge-margin 2.0 --out "$out/other.byrg" > /dev/null
expect_bad "$out/other.byrg" "other.byrg was built for another racing line"
mkfifo "$out/fifo.byrg"  # no writer: opening it to read would wait for ever
expect_bad "$out/fifo.byrg" "fifo.byrg: not a regular file"
echo "road_graph_file: ok"
