#!/usr/bin/env bash
# A split run on the sim clock whose peer dies (issue 19): process b of a supervised lockstep run
# is killed with SIGKILL; process a, waiting on b's next event, must say within 1.5 s of the last
# thing it heard from b that b went silent, and the run must fail (exit 1) naming it — never hang,
# never "success". (1.5 s: the liveliness lease is 0.5 s; the rest is slack for a loaded machine.)
# That silence is a's own measure, in its reason; what this script sees of the log is only bounded
# (15 s: no hang): under a loaded CTest the supervisor's relay and this poll were once 5 s late.
# usage: lockstep_peer_killed.sh BRICKYARD GRAPH DOMAIN OUT
set -u
by=$1; graph=$2; domain=$3; out=$4
rm -rf "$out"; mkdir -p "$out"
# Paced at real time, so the run is still going when b dies.
"$by" run "$graph" --domain "$domain" --duration 1000 --set check.finish_after=0 --pace 1 --out "$out/run" --no-report 2> "$out/run.log" &
sup=$!
. "$(dirname "$0")/supervised_child.sh"
pid=$(child_pid b "$out/run.log")
[ -n "$pid" ] || { echo "FAIL: process b never started"; cat "$out/run.log"; kill $sup; exit 1; }
sleep 2
kill -9 "$pid"
killed=$(date +%s.%N)
said=""
for _ in $(seq 1 1500); do
  if grep -q "\[a\] .*lockstep: process 'b' went silent" "$out/run.log"; then said=$(date +%s.%N); break; fi
  sleep 0.01
done
wait $sup
rc=$?
cat "$out/run.log" | tail -n 6
[ "$rc" = 1 ] || { echo "FAIL: exit $rc, expected 1"; exit 1; }
[ -n "$said" ] || { echo "FAIL: process a did not say within 15 s that b went silent"; exit 1; }
delay=$(python3 -c "print(f'{$said - $killed:.2f}')")
silent=$(sed -n "s/.*\[a\] .*process 'b' went silent (nothing from it for \([0-9.]*\) s.*/\1/p" "$out/run.log" | head -n 1)
[ -n "$silent" ] || { echo "FAIL: a's reason does not say how long b was silent"; exit 1; }
echo "process a said b went silent $silent s after the last it heard from b (this script read it $delay s after the kill)"
python3 -c "import sys; sys.exit(0 if $silent <= 1.5 else 1)" || { echo "FAIL: more than 1.5 s"; exit 1; }
python3 - "$out/run/a/summary.json" <<'PY' || exit 1
import json, sys
s = json.load(open(sys.argv[1]))
ok = s["result"] == "failed" and "process 'b' went silent" in s["reason"]
print(("" if ok else "FAIL: ") + f"process a: {s['result']}: {s['reason']} (wall {s['wall_time_s']:.2f} s)")
sys.exit(0 if ok else 1)
PY
echo "a lockstep run whose peer was killed failed, naming it"
