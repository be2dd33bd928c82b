#!/usr/bin/env bash
# A process of a split run killed (SIGKILL: no goodbye on the wire): the other process notices
# within the writers' liveliness lease (0.5 s) and says so at once, naming the input, the silent
# writer and its process; it runs on (a car interface keeps braking the car) and its run fails at
# its end with that reason, in the summary too (docs/reliability.md). Before, it ended "success".
set -u
by=$1; graph=$2; domain=$3; out=$4
rm -rf "$out"; mkdir -p "$out"
"$by" run "$graph" --process b --domain "$domain" --duration 6 --set check.min_count=0 --set check.min_rate_hz=0 \
  --out "$out/b" > "$out/b.log" 2>&1 &
pid_b=$!
"$by" run "$graph" --process a --domain "$domain" --duration 60 > "$out/a.log" 2>&1 &
pid_a=$!
sleep 3  # the two have met and samples flow
kill -9 $pid_a
# The warning: b measures its writer's silence itself (its steady clock since the last sample,
# 50 a second until the kill); timed from outside, a shell polling a log under a loaded CTest
# measures its own delays. The poll only guards against a warning that never comes.
for i in $(seq 300); do grep -q "warning: input double.in" "$out/b.log" && break; sleep 0.05; done
wait $pid_b; rc_b=$?
grep "warning\|failed" "$out/b.log" | head -3
silent=$(grep -o "nothing from it for [0-9.]* s" "$out/b.log" | head -1 | grep -o "[0-9.]*")
echo "b said a's writer had been silent $silent s, ran on to its end, exit $rc_b"
[ -n "$silent" ] || { echo "FAIL: b never said how long its writer had been silent"; exit 1; }
python3 -c "import sys; sys.exit(0 if float('$silent') < 1.5 else 1)" || { echo "FAIL: b noticed $silent s after the last sample"; exit 1; }
grep -q "warning: input double.in: its writer src.out (process 'a') went silent: no liveliness for 0.5 s, nothing from it for [0-9.]* s (did the process die?) at t = [0-9.]* s; the run goes on" "$out/b.log" \
  || { echo "FAIL: the warning does not name the input and its writer"; exit 1; }
[ $rc_b -eq 1 ] || { echo "FAIL: b did not fail when its peer died"; exit 1; }
grep -q '"reason": "input double.in: its writer src.out' "$out/b/summary.json" && grep -q '"lost_peers"' "$out/b/summary.json" \
  || { echo "FAIL: the summary lacks the reason"; exit 1; }
echo "peer_lost: ok"
