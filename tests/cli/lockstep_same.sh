#!/usr/bin/env bash
# One sim clock across processes (issue 19): a split graph on the sim clock, supervised (its
# processes in lockstep over DDS), on one thread and on four, is the same run as in one process —
# the same exit code, verdict, per-node summary and recording (lockstep_same.py says what).
# usage: lockstep_same.sh BRICKYARD GRAPH DOMAIN OUT [run options...]
set -u
by=$1; graph=$2; domain=$3; out=$4; shift 4
rm -rf "$out"; mkdir -p "$out"
"$by" run "$graph" --one-process --domain "$domain" --quiet --progress 0 --out "$out/one" "$@" 2> "$out/one.log"
rc_one=$?
tail -n 1 "$out/one.log"
[ "$rc_one" -le 2 ] || { echo "FAIL: one process: exit $rc_one"; exit 1; }
for n in 1 4; do
  "$by" run "$graph" --threads "$n" --domain "$domain" --quiet --progress 0 --out "$out/split$n" "$@" 2> "$out/split$n.log"
  rc=$?
  tail -n 1 "$out/split$n.log"
  [ "$rc" = "$rc_one" ] || { echo "FAIL: exit $rc split over processes ($n thread(s)), $rc_one in one"; cat "$out/split$n.log"; exit 1; }
  python3 "$(dirname "$0")/lockstep_same.py" "$out/one" "$out/split$n" || exit 1
done
echo "the same run split over processes as in one (exit $rc_one)"
