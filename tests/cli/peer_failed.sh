#!/usr/bin/env bash
# A split run started by hand on the real clock (tests/graphs/multiprocess/two_process_fault.json):
# process a's source fails 2 s in, by a throw or by exit(); process b, healthy, runs on to its end
# and must fail naming a's failure (a peer that leaves cleanly lapses no liveliness, and exit()
# leaves cleanly: before, b ended "success"). With no fault both pass. docs/reliability.md.
set -u
by=$1; graph=$2; domain=$3; out=$4
rm -rf "$out"; mkdir -p "$out"
run_pair() {  # fault -> b's exit code; logs and summaries in $out/$fault
  local fault=$1 dir=$out/$1
  mkdir -p "$dir"
  "$by" run "$graph" --process b --domain "$domain" --duration 4 --arg fault="$fault" --out "$dir/b" > "$dir/b.log" 2>&1 &
  local pb=$!
  "$by" run "$graph" --process a --domain "$domain" --duration 4 --arg fault="$fault" --out "$dir/a" > "$dir/a.log" 2>&1
  echo $? > "$dir/a.rc"
  wait $pb
}
expect() {  # fault, b's exit code, the reason b's summary must give
  local fault=$1 rc_want=$2 reason=$3 rc
  run_pair "$fault"; rc=$?
  grep -h "warning\|\] failed\|\] success" "$out/$fault/b.log" | head -3
  [ "$rc" -eq "$rc_want" ] || { tail -5 "$out/$fault/a.log" "$out/$fault/b.log"; echo "FAIL ($fault): b exited $rc, not $rc_want"; exit 1; }
  grep -q "\"reason\": \"$reason" "$out/$fault/b/summary.json" || { echo "FAIL ($fault): b's summary does not say: $reason"; exit 1; }
}
expect throw 1 "process 'a' failed: node 'src' (testing.fault) failed in step: fault injected: throw at step 100"
grep -q '"failed_peers"' "$out/throw/b/summary.json" || { echo "FAIL: b's summary lacks failed_peers"; exit 1; }
grep -q "warning: process 'a' failed: .* (at t = [0-9.]* s); the run goes on, and fails at its end" "$out/throw/b.log" \
  || { echo "FAIL: b did not say a's failure when it heard it"; exit 1; }
expect exit 1 "process 'a' left without saying how its run ended"
expect none 0 "duration reached"
[ "$(cat "$out/none/a.rc")" -eq 0 ] || { echo "FAIL: a failed with no fault"; exit 1; }
echo "peer_failed: ok"
