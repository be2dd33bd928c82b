#!/usr/bin/env bash
# Two brickyard processes, one graph: process a publishes, process b transforms and asserts.
# The wires between them are Fast DDS topics; b's assertion sink must pass.
# Discovery between processes takes a variable time on a loaded machine (CI ran this beside 85
# other tests), so b ends on the 50th sample rather than on a fixed duration, and a runs until
# b is done (Ctrl-C, a clean shutdown). The durations are only a guard against a hang.
set -u
by=$1; graph=$2; domain=$3; out=$4
rm -rf "$out"; mkdir -p "$out"
"$by" run "$graph" --process b --domain "$domain" --duration 60 --set check.finish_after=50 \
  --out "$out/b" > "$out/b.log" 2>&1 &
pid_b=$!
"$by" run "$graph" --process a --domain "$domain" --duration 60 --out "$out/a" > "$out/a.log" 2>&1 &
pid_a=$!
wait $pid_b; rc_b=$?
kill -INT $pid_a 2>/dev/null
wait $pid_a; rc_a=$?
echo "--- process a (exit $rc_a)"; cat "$out/a.log"
echo "--- process b (exit $rc_b)"; cat "$out/b.log"
[ $rc_a -eq 0 ] && [ $rc_b -eq 0 ] || { echo "FAIL"; exit 1; }
grep -q '"passed": 1.0' "$out/b/summary.json" || { echo "FAIL: sink did not pass"; exit 1; }
grep -q 'received 50 samples' "$out/b.log" || { echo "FAIL: b did not end on its 50th sample"; exit 1; }
grep -A3 '"count"' "$out/b/summary.json" | head -3
echo "two processes exchanged typed messages over DDS"
