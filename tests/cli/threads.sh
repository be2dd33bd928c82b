#!/usr/bin/env bash
# A sim-clock run is the same on one thread and on four: the same exit code, summary (but for
# wall time) and recording, sample for sample. The executive steps nodes side by side on four
# (docs/performance.md); this is the proof that nothing of the run depends on it.
# usage: threads.sh BRICKYARD GRAPH DOMAIN OUT [run options...]
set -u
by=$1; graph=$2; domain=$3; out=$4; shift 4
rm -rf "$out"; mkdir -p "$out"
declare -A rc
for n in 1 4; do
  "$by" run "$graph" --threads "$n" --domain "$domain" --quiet --progress 0 --out "$out/t$n" "$@" 2> "$out/t$n.log"
  rc[$n]=$?
  tail -n 1 "$out/t$n.log"
done
[ "${rc[1]}" = "${rc[4]}" ] || { echo "FAIL: exit ${rc[1]} on one thread, ${rc[4]} on four"; exit 1; }
[ "${rc[1]}" -le 1 ] || { echo "FAIL: exit ${rc[1]}"; exit 1; }
strip() { grep -v '"wall_time_s"' "$1"; }
if ! diff <(strip "$out/t1/summary.json") <(strip "$out/t4/summary.json"); then
  echo "FAIL: one thread and four, different summaries"; exit 1
fi
diff <(tail -n 1 "$out/t1.log" | sed 's/, wall [0-9.]* s//') <(tail -n 1 "$out/t4.log" | sed 's/, wall [0-9.]* s//') \
  || { echo "FAIL: different verdicts"; exit 1; }
python3 "$(dirname "$0")/same_recordings.py" "$out/t1/recording.mcap" "$out/t4/recording.mcap" || { echo "FAIL: one thread and four, different recordings"; exit 1; }
echo "the same run on one thread and on four (exit ${rc[1]})"
