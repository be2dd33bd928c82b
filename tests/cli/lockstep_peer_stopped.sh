#!/usr/bin/env bash
# A split run on the sim clock whose peer stops without dying (SIGSTOP: a process held by
# something its own watchdogs cannot see): process a says b went silent and ends; the supervisor
# must not wait for b for ever ("the others, in lockstep with it, end too"): past
# transport.end_timeout_s (1 s here) and its slack (10 s) after a's end it stops b, killing it
# past the grace, and the run fails naming b. Before, it waited until CTest killed it.
# usage: lockstep_peer_stopped.sh BRICKYARD GRAPH DOMAIN OUT
set -u
by=$1; graph=$2; domain=$3; out=$4
rm -rf "$out"; mkdir -p "$out"
# Paced at real time, so the run is still going when b stops.
timeout 90 "$by" run "$graph" --domain "$domain" --duration 1000 --set check.finish_after=0 --pace 1 --arg end_timeout_s=1 \
  --out "$out/run" --no-report 2> "$out/run.log" &
sup=$!
. "$(dirname "$0")/supervised_child.sh"
pid=$(child_pid b "$out/run.log")
[ -n "$pid" ] || { echo "FAIL: process b never started"; cat "$out/run.log"; kill $sup; exit 1; }
sleep 1
kill -STOP "$pid"
stopped=$(date +%s.%N)
wait $sup
rc=$?
took=$(python3 -c "import time; print(f'{time.time() - $stopped:.1f}')")
tail -n 6 "$out/run.log"
[ "$rc" != 124 ] || { echo "FAIL: the supervisor was still waiting for b 90 s on"; kill -9 "$pid"; exit 1; }
[ "$rc" = 1 ] || { echo "FAIL: exit $rc, expected 1"; exit 1; }
grep -q "\[a\] .*lockstep: process 'b' went silent" "$out/run.log" || { echo "FAIL: a did not say b went silent"; exit 1; }
grep -q "process 'b' did not end within 11 s of process 'a''s end" "$out/run.log" || { echo "FAIL: the supervisor did not name b"; exit 1; }
python3 - "$out/run/summary.json" <<'PY' || exit 1
import json, sys
s = json.load(open(sys.argv[1]))
runs = s["processes"]["b"]["runs"]
ok = s["result"] == "failed" and runs and runs[-1].get("signal") == "SIGKILL"
print(("" if ok else "FAIL: ") + f"the run: {s['result']}: {s['reason']}; b: {runs[-1] if runs else 'no run'}")
sys.exit(0 if ok else 1)
PY
echo "a stopped peer was stopped by its supervisor $took s after it stopped, named; the run failed"
