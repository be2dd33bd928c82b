#!/usr/bin/env bash
# A receiver that reboots (docs/drivers-transports.md, "Reopening"), in a private network
# namespace (scripts/netns-run: loopback only): a receiver's TCP port (tcp_receiver_restarts.py)
# sends 20 BESTPOSA logs, closes, listens again 0.5 s later and sends 20 more; drivers.gnss, its
# client with reopen=0.2, must publish all 40 fixes, say the failure and the port open again, and
# count as many reopenings as failures. With reopen=0 it gets the first 20 only (the test of the
# test: the graph then fails).
set -u
by=$1; graphs=$2; domain=$3; out=$4
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$out"; mkdir -p "$out"
fail() { echo "FAIL: $*"; exit 1; }
python3 "$here/capture_logs.py" "$out" || fail "making the GNSS logs"

# run REOPEN NAME: the receiver and the driver's graph; the graph's exit status.
run() {
  python3 "$here/tcp_receiver_restarts.py" "$out/oem7_20hz.GPS" "$out/$2.port" > "$out/$2.receiver.log" 2>&1 &
  local receiver=$! port
  for _ in $(seq 200); do [ -s "$out/$2.port" ] && break; sleep 0.05; done
  port=$(cat "$out/$2.port" 2> /dev/null) || fail "the receiver did not start"
  "$by" run "$graphs/gnss_reopen.json" --set "gnss.source=tcp://127.0.0.1:$port?reopen=$1" --domain "$domain" \
    --out "$out/$2" > "$out/$2.log" 2>&1
  local rc=$?
  kill "$receiver" 2> /dev/null; wait "$receiver" 2> /dev/null
  return $rc
}

run 0.2 reopen || { cat "$out/reopen.log"; fail "drivers.gnss did not publish the 40 fixes across the receiver's restart"; }
grep -q "closed by the peer: no more fixes from it until it opens again" "$out/reopen.log" || { cat "$out/reopen.log"; fail "the failure was not said"; }
grep -q "source open again: fixes from it again" "$out/reopen.log" || { cat "$out/reopen.log"; fail "the reopening was not said"; }
# Each open tried while the port is closed is refused (another failure), so as many reopenings as
# failures, the last one connected.
grep -Eq "device_failures ([1-9][0-9]*) · device_reopened \1 " "$out/reopen.log" || { cat "$out/reopen.log"; fail "the driver's counts"; }
run 0 never && { cat "$out/never.log"; fail "with reopen=0 the graph passed: it cannot tell"; }
grep -q "count.*20" "$out/never.log" || { cat "$out/never.log"; fail "with reopen=0, not the first 20 fixes"; }
grep -q "closed by the peer: no more fixes from it$" "$out/never.log" || { cat "$out/never.log"; fail "with reopen=0, the failure said as if it would open again"; }
echo "gnss_reopen: ok"
