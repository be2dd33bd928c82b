#!/usr/bin/env bash
# A plugin that fails or takes its process down in a split run on the sim clock (issue 19): for
# each fault testing.fault injects at its step 120 in process a — an exception, a segmentation
# fault, abort(), exit(0) — the supervised run ends with exit 1 naming the node and the fault,
# process b ends too (the throw: with the same verdict, at the same event; a crash: b says that a
# went silent, or left), every process has a summary, and no shared memory is left in /dev/shm.
# usage: lockstep_faults.sh BRICKYARD GRAPH DOMAIN OUT
set -u
by=$1; graph=$2; domain=$3; out=$4
rm -rf "$out"; mkdir -p "$out"
ports="fastrtps_port($(seq -s '|' $((7400 + 250 * domain + 10)) $((7400 + 250 * domain + 29))))\b"
for f in $(ls /dev/shm | grep -E "$ports" || true); do rm -f "/dev/shm/$f"; done
for mode in throw segfault abort exit; do
  dir="$out/$mode"
  timeout 60 "$by" run "$graph" --domain "$domain" --progress 0 --set fault.mode=$mode --out "$dir" --no-report > "$dir.log" 2>&1
  rc=$?
  case $mode in
    throw) want="node 'fault' (testing.fault) failed in step: fault injected: throw at step 120" ;;
    segfault) want="node 'fault' crashed with SIGSEGV (a segmentation fault) in its step" ;;
    abort) want="node 'fault' crashed with SIGABRT (abort) in its step" ;;
    exit) want="node 'fault' called exit() in its step" ;;
  esac
  [ $rc -eq 1 ] || { cat "$dir.log"; echo "FAIL: $mode: exit $rc, expected 1"; exit 1; }
  grep -qF "$want" "$dir.log" || { cat "$dir.log"; echo "FAIL: $mode: the output lacks: $want"; exit 1; }
  for p in a b; do
    [ -s "$dir/$p/summary.json" ] || { cat "$dir.log"; echo "FAIL: $mode: no summary of process $p"; exit 1; }
  done
  python3 - "$dir" "$mode" "$want" <<'PY' || { cat "$dir.log"; exit 1; }
import json, sys
d, mode, want = sys.argv[1:4]
sup, a, b = (json.load(open(f"{d}/{p}summary.json")) for p in ("", "a/", "b/"))
fail = []
if sup["result"] != "failed" or want not in sup["reason"]: fail.append(f"the supervisor's verdict: {sup['result']}: {sup['reason']}")
if a["result"] != "failed" or want not in a["reason"]: fail.append(f"process a: {a['result']}: {a['reason']}")
if mode == "throw":
    # The stop travels in a's record: b ends at the same event with the same verdict.
    if (b["result"], b["reason"], b["sim_time_s"]) != (a["result"], a["reason"], a["sim_time_s"]):
        fail.append(f"process b: {b['result']}: {b['reason']} at {b['sim_time_s']} s, a at {a['sim_time_s']} s")
elif b["result"] != "failed" or "lockstep: process 'a'" not in b["reason"]:
    fail.append(f"process b: {b['result']}: {b['reason']}")
for f in fail: print(f"FAIL: {mode}: {f}")
if not fail: print(f"{mode}: a: {a['reason']} | b: {b['reason']}")
sys.exit(1 if fail else 0)
PY
  left=$(ls /dev/shm | grep -E "$ports" || true)
  [ -z "$left" ] || { echo "$left"; echo "FAIL: $mode: shared memory left in /dev/shm"; exit 1; }
done
echo "every fault in a split run on the sim clock: named, both processes ended, summaries written, nothing left"
