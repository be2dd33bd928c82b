#!/usr/bin/env bash
# A plugin that takes its process down (docs/reliability.md): for each fault testing.fault can
# inject at its step 120 — an exception, a segmentation fault, abort(), exit(0) — on the sim and
# the real clock, the run ends with exit 1, stderr names the node, the phase and the fault,
# summary.json is written with the reason, the recording keeps all but the last second before the
# fault, and no shared memory is left in /dev/shm. A node that
# hangs in its step: SIGINT ends the run within 2 s naming it (exit 130), and a second signal
# ends it at once; a real-clock run that reaches its end fails 2 s later naming it (exit 1). A node's step deadline (deadline_s): a late step fails the run, a stuck one
# ends it.
set -u
by=$1; graphs=$2; domain=$3; out=$4
rm -rf "$out"; mkdir -p "$out"
# This domain's port files (7400 + 250 x domain + 10 and 11), their lock files and semaphores:
# what a run leaves is what was not there before it (a process killed outside this test, on the
# same domain, leaves its own behind: /dev/shm is the machine's, not the test's).
ports() { ls /dev/shm | grep -E "fastrtps_port($((7400 + 250 * domain + 10))|$((7400 + 250 * domain + 11)))" || true; }
before=$(ports)
for clock in sim real; do
  for mode in throw segfault abort exit; do
    dir="$out/$clock-$mode"
    graph="$graphs/fault.json"; [ $clock = real ] && graph="$graphs/fault_real.json"
    "$by" run "$graph" --domain "$domain" --quiet --progress 0 --set fault.mode=$mode \
      --out "$dir" --record "$out/$clock-$mode.mcap" > "$dir.log" 2>&1 &
    pid=$!
    wait $pid; rc=$?
    case $mode in
      throw) want="node 'fault' (testing.fault) failed in step: fault injected: throw at step 120" ;;
      segfault) want="node 'fault' crashed with SIGSEGV (a segmentation fault) in its step" ;;
      abort) want="node 'fault' crashed with SIGABRT (abort) in its step" ;;
      exit) want="node 'fault' called exit() in its step" ;;
    esac
    [ $rc -eq 1 ] || { cat "$dir.log"; echo "FAIL: $clock/$mode: exit $rc, expected 1"; exit 1; }
    grep -qF "$want" "$dir.log" || { cat "$dir.log"; echo "FAIL: $clock/$mode: stderr lacks: $want"; exit 1; }
    grep -qF "$want" "$dir/summary.json" || { cat "$dir/summary.json"; echo "FAIL: $clock/$mode: the summary lacks the reason"; exit 1; }
    # What was published up to a second before the fault is in the recording. A run that ends
    # (throw) closes it under its name; one the fault takes down cannot, and it stays .part:
    # a file under the name is always a whole recording.
    rec="$out/$clock-$mode.mcap"
    if [ $mode = throw ]; then
      [ -e "$rec" ] && [ ! -e "$rec.part" ] || { echo "FAIL: $clock/$mode: the recording was not closed under its name"; exit 1; }
    else
      [ ! -e "$rec" ] && [ -e "$rec.part" ] || { echo "FAIL: $clock/$mode: an unclosed recording took its name"; exit 1; }
      rec="$rec.part"
    fi
    "$by" bag info "$rec" --json > "$dir.info.json" 2> /dev/null
    python3 - "$dir.info.json" "$clock" "$mode" <<'PY' || exit 1
import json, sys
info = json.load(open(sys.argv[1]))
n = {t["name"]: t["count"] for t in info["topics"]}.get("fault.out", 0)
print(f"{sys.argv[2]}/{sys.argv[3]}: exit 1, named; the recording kept {n} of the 120 samples before the fault")
sys.exit(0 if n >= 70 else 1)  # all but the last second's 50, at most
PY
    # Its Fast DDS shared memory is gone: the participant's port files, named by this test's own
    # domain, their lock files and semaphores.
    left=$(comm -13 <(echo "$before") <(ports))
    [ -z "$left" ] || { echo "$left"; echo "FAIL: $clock/$mode: the process left its shared memory in /dev/shm"; exit 1; }
  done
done
# A node stuck in its step: SIGINT, and the run ends within 2 s (the watchdog), named.
"$by" run "$graphs/fault.json" --domain "$domain" --quiet --progress 0 --set fault.mode=hang --duration 600 --out "$out/hang" \
  > "$out/hang.log" 2>&1 &
pid=$!
sleep 1.5
start=$(date +%s%N)
kill -INT $pid
wait $pid; rc=$?
took=$(( ($(date +%s%N) - start) / 1000000 ))
echo "hang: SIGINT, exit $rc after $took ms"
[ $rc -eq 130 ] && [ $took -lt 3000 ] || { cat "$out/hang.log"; echo "FAIL: a hung node kept the run past 2 s of SIGINT"; exit 1; }
grep -qF "the run did not stop within 2 s of the signal: node 'fault' (in its step); forced exit" "$out/hang.log" \
  || { cat "$out/hang.log"; echo "FAIL: the hung node was not named"; exit 1; }
grep -q '"result": "interrupted"' "$out/hang/summary.json" || { cat "$out/hang/summary.json"; echo "FAIL: no summary"; exit 1; }
# A second signal: at once.
"$by" run "$graphs/fault.json" --domain "$domain" --quiet --progress 0 --set fault.mode=hang --duration 600 > "$out/hang2.log" 2>&1 &
pid=$!
sleep 1.5
start=$(date +%s%N)
kill -INT $pid; sleep 0.2; kill -TERM $pid
wait $pid; rc=$?
took=$(( ($(date +%s%N) - start) / 1000000 ))
echo "hang: two signals, exit $rc after $took ms"
[ $rc -eq 130 ] && [ $took -lt 1000 ] && grep -qF "a second signal: node 'fault' (in its step); forced exit" "$out/hang2.log" \
  || { cat "$out/hang2.log"; echo "FAIL: a second signal did not force the exit"; exit 1; }
# A real-clock run of 4 s whose node hangs at step 120 (2.4 s): at its end the run has 2 s to
# stop, then fails naming the node (it stayed alive for ever, saying nothing).
start=$(date +%s%N)
# (Its deadline set far off: the derived one would end the hang first, as below.)
timeout 20 "$by" run "$graphs/fault_real.json" --domain "$domain" --quiet --progress 0 --set fault.mode=hang --duration 4 \
  --set fault.step_deadline_s=3600 --out "$out/hang_at_end" > "$out/hang_at_end.log" 2>&1
rc=$?
took=$(( ($(date +%s%N) - start) / 1000000 ))
echo "hang: a 4 s real-clock run with a hung node ended after $took ms, exit $rc"
[ $rc -eq 1 ] && [ $took -lt 9000 ] && grep -qF "the run reached its end but did not stop within 2 s: node 'fault' (in its step); forced exit" "$out/hang_at_end.log" \
  && grep -q '"result": "failed"' "$out/hang_at_end/summary.json" || { cat "$out/hang_at_end.log"; echo "FAIL: a hung node kept an ended run alive"; exit 1; }
# Step deadlines (deadline_s 0.3 s): a step that takes 0.8 s fails the run when it returns; one
# that never returns is given up on at 1.3 s (twice the deadline, at least a second past it).
"$by" run "$graphs/fault_deadline.json" --domain "$domain" --quiet --progress 0 --set fault.mode=slow --out "$out/slow" > "$out/slow.log" 2>&1
rc=$?
[ $rc -eq 1 ] && grep -q "node 'fault' (testing.fault)'s step took 0.8[0-9]* s, past its deadline of 0.300 s" "$out/slow.log" \
  && grep -q '"result": "failed"' "$out/slow/summary.json" || { cat "$out/slow.log"; echo "FAIL: a step past its deadline"; exit 1; }
start=$(date +%s%N)
"$by" run "$graphs/fault_deadline.json" --domain "$domain" --quiet --progress 0 --set fault.mode=hang --duration 600 > "$out/stuck.log" 2>&1
rc=$?
took=$(( ($(date +%s%N) - start) / 1000000 ))
echo "deadline: a slow step failed the run; a stuck step ended it after $took ms, exit $rc"
[ $rc -eq 1 ] && [ $took -lt 4000 ] && grep -q "node 'fault' has been in its step for 1.[0-9] s, far past its step deadline" "$out/stuck.log" \
  || { cat "$out/stuck.log"; echo "FAIL: a step stuck past its deadline"; exit 1; }
# The deadline as the plugin's parameter (Manifest::step_deadline), no deadline_s in the graph.
"$by" run "$graphs/fault.json" --domain "$domain" --quiet --progress 0 --set fault.mode=slow --set fault.step_deadline_s=0.3 > "$out/param.log" 2>&1
rc=$?
[ $rc -eq 1 ] && grep -q "node 'fault' (testing.fault)'s step took 0.8[0-9]* s, past its deadline of 0.300 s" "$out/param.log" \
  || { cat "$out/param.log"; echo "FAIL: the manifest's step deadline"; exit 1; }
echo "deadline: the plugin's own step_deadline_s parameter holds too"
# Deadlines by default (docs/reliability.md): no deadline_s and the plugin's parameter 0, the node
# gets ten of its periods, at least 0.5 s. On the real clock the 0.8 s step fails the run naming
# that deadline, and a hung step is ended 1.5 s in; on the sim clock the slow step passes (a slow
# machine must not change a sim run's result) and only a step stuck for 30 s would be ended.
"$by" run "$graphs/fault_real.json" --domain "$domain" --quiet --progress 0 --set fault.mode=slow --out "$out/slow_real" > "$out/slow_real.log" 2>&1
rc=$?
[ $rc -eq 1 ] && grep -q "node 'fault' (testing.fault)'s step took 0.8[0-9]* s, past its deadline of 0.500 s (derived from its trigger" "$out/slow_real.log" \
  && grep -q '"result": "failed"' "$out/slow_real/summary.json" || { cat "$out/slow_real.log"; echo "FAIL: the derived deadline on the real clock"; exit 1; }
start=$(date +%s%N)
timeout 20 "$by" run "$graphs/fault_real.json" --domain "$domain" --quiet --progress 0 --set fault.mode=hang --duration 600 > "$out/hang_real.log" 2>&1
rc=$?
took=$(( ($(date +%s%N) - start) / 1000000 ))
[ $rc -eq 1 ] && [ $took -lt 6000 ] && grep -q "node 'fault' has been in its step for 1.[0-9] s, far past its step deadline" "$out/hang_real.log" \
  || { cat "$out/hang_real.log"; echo "FAIL: a hang past the derived deadline (exit $rc after $took ms)"; exit 1; }
"$by" run "$graphs/fault.json" --domain "$domain" --quiet --progress 0 --set fault.mode=slow > "$out/slow_sim.log" 2>&1
rc=$?
[ $rc -eq 0 ] || { cat "$out/slow_sim.log"; echo "FAIL: a slow step failed a sim-clock run by a derived deadline"; exit 1; }
echo "deadline by default: a slow step failed the real-clock run, a hung one was ended after $took ms; the sim run passed"
# A writer alive but silent (mode silent at step 120): its reader's input is stale — in the
# summary on the sim clock (1.62 s without a sample at the end, against its usual 0.02 s), and on
# the real clock's progress line.
"$by" run "$graphs/fault.json" --domain "$domain" --quiet --progress 0 --set fault.mode=silent --out "$out/silent" > "$out/silent.log" 2>&1
python3 - "$out/silent/summary.json" <<'PY' || { cat "$out/silent.log"; echo "FAIL: a silent input is not stale in the summary"; exit 1; }
import json, sys
s = json.load(open(sys.argv[1]))
st = s.get("stale_inputs", [])
assert len(st) == 1 and st[0]["input"] == "check.in" and st[0]["stale_at_end"] and abs(st[0]["max_gap_s"] - 1.62) < 1e-9, st
assert abs(st[0]["usual_interval_s"] - 0.02) < 1e-9, st
PY
"$by" run "$graphs/fault_real.json" --domain "$domain" --progress 0.5 --set fault.mode=silent > "$out/silent_real.log" 2>&1
grep -qE "progress: t [0-9.]+ s .*stale check.in [0-9.]+ s" "$out/silent_real.log" \
  || { cat "$out/silent_real.log"; echo "FAIL: a silent input is not stale on the progress line"; exit 1; }
echo "silent: the input is stale in the summary (sim) and on the progress line (real)"
echo "faults: ok"
