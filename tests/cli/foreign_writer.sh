#!/usr/bin/env bash
# A writer the graph does not name (issue 20): process b of a split run (tests/graphs/
# multiprocess/two_process.json) takes double.in from process a's src.out; `brickyard bag play`
# of a recording of src.out ramping from 1000 sends to the same topic from another participant,
# as a forger would. b must drop every forged sample (its sink's largest value stays that of a's
# ramp), say which writer it was, and list it in its summary.
set -u
by=$1; graph=$2; domain=$3; out=$4
rm -rf "$out"; mkdir -p "$out"
"$by" run "$graph" --one-process --domain "$domain" --quiet --progress 0 --duration 4 --set src.start=1000 \
  --set check.min_count=0 --record "$out/forged.mcap" --record-only src.out > "$out/rec.log" 2>&1 \
  || { cat "$out/rec.log"; echo "FAIL: recording the forger's samples"; exit 1; }
"$by" run "$graph" --process b --domain "$domain" --progress 0 --duration 20 --set check.finish_after=200 \
  --set check.max_value=999 --out "$out/b" > "$out/b.log" 2>&1 &
pid_b=$!
"$by" run "$graph" --process a --domain "$domain" --quiet --progress 0 --duration 30 > "$out/a.log" 2>&1 &
pid_a=$!
sleep 1
"$by" bag play "$out/forged.mcap" --domain "$domain" > "$out/play.log" 2>&1
wait $pid_b; rc=$?
kill -INT $pid_a 2>/dev/null; wait $pid_a
grep "writer the graph does not name" "$out/b.log" | head -2
[ $rc -eq 0 ] || { cat "$out/b.log" "$out/play.log"; echo "FAIL: b exited $rc (a forged sample reached its sink?)"; exit 1; }
python3 - "$out/b/summary.json" <<'PY' || exit 1
import json, sys
s = json.load(open(sys.argv[1]))
fw = s.get("foreign_writers", [])
m = s["nodes"]["check"]["metrics"]
print(f"forged writers seen: {len(fw)} ({fw[0]['participant'] if fw else '-'}), all dropped; b's sink: {m['count']:.0f} samples, largest {m['max']:.0f}")
sys.exit(0 if fw and fw[0]["input"] == "double.in" and not fw[0]["accepted"] and m["max"] < 1000 and m["count"] >= 200 else 1)
PY
echo "foreign_writer: ok"
