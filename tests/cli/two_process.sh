#!/usr/bin/env bash
# Two brickyard processes, one graph: process a publishes, process b transforms and asserts.
# The wires between them are Fast DDS topics; b's assertion sink must pass.
set -u
by=$1; graph=$2; domain=$3; out=$4
rm -rf "$out"; mkdir -p "$out"
"$by" run "$graph" --process b --domain "$domain" --duration 4.5 --out "$out/b" > "$out/b.log" 2>&1 &
pid_b=$!
sleep 0.5
"$by" run "$graph" --process a --domain "$domain" --duration 3.5 --out "$out/a" > "$out/a.log" 2>&1
rc_a=$?
wait $pid_b; rc_b=$?
echo "--- process a (exit $rc_a)"; cat "$out/a.log"
echo "--- process b (exit $rc_b)"; cat "$out/b.log"
[ $rc_a -eq 0 ] && [ $rc_b -eq 0 ] || { echo "FAIL"; exit 1; }
grep -q '"passed": 1.0' "$out/b/summary.json" || { echo "FAIL: sink did not pass"; exit 1; }
grep -A3 '"count"' "$out/b/summary.json" | head -3
echo "two processes exchanged typed messages over DDS"
