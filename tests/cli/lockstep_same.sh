#!/usr/bin/env bash
# One sim clock across processes (issue 19): a split graph on the sim clock, supervised (its
# processes in lockstep over DDS), on one thread and on four, is the same run as in one process —
# the same exit code, verdict, per-node summary and recording (lockstep_same.py says what).
# BY_SECURE=1 (a graph without --arg): the split runs secured (security init's default: authenticated, every message
# encrypted; the clock topics in the permissions), the one-process run not: still the same run.
# usage: lockstep_same.sh BRICKYARD GRAPH DOMAIN OUT [run options...]
set -u
by=$1; graph=$2; domain=$3; out=$4; shift 4
rm -rf "$out"; mkdir -p "$out"
split_graph=$graph
if [ -n "${BY_SECURE:-}" ]; then
  split_graph=$out/secure.json
  python3 -c "import json,sys; g=json.load(open(sys.argv[1])); g['transport']=dict(g.get('transport',{}), security=sys.argv[2]); json.dump(g, open(sys.argv[3],'w'))" \
    "$graph" "$out/keys" "$split_graph" || exit 1
  "$by" security init "$split_graph" --out "$out/keys" > "$out/init.log" 2>&1 || { cat "$out/init.log"; echo "FAIL: security init"; exit 1; }
  grep -q "<topic>brickyard_clock/b</topic>" "$out/keys/a/permissions.xml" || { echo "FAIL: a may not read b's clock"; exit 1; }
fi
"$by" run "$graph" --one-process --domain "$domain" --quiet --progress 0 --out "$out/one" "$@" 2> "$out/one.log"
rc_one=$?
tail -n 1 "$out/one.log"
[ "$rc_one" -le 2 ] || { echo "FAIL: one process: exit $rc_one"; exit 1; }
for n in 1 4; do
  "$by" run "$split_graph" --threads "$n" --domain "$domain" --quiet --progress 0 --out "$out/split$n" "$@" 2> "$out/split$n.log"
  rc=$?
  tail -n 1 "$out/split$n.log"
  [ "$rc" = "$rc_one" ] || { echo "FAIL: exit $rc split over processes ($n thread(s)), $rc_one in one"; cat "$out/split$n.log"; exit 1; }
  python3 "$(dirname "$0")/lockstep_same.py" "$out/one" "$out/split$n" || exit 1
done
echo "the same run split over processes as in one (exit $rc_one)"
