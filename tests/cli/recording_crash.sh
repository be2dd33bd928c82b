#!/usr/bin/env bash
# A run killed mid-way (SIGKILL: no handler, no close) keeps its recording up to its last second:
# samples are committed at least once a second, not only every 2000 (a slow run killed at 4 s
# had committed none of its 150 samples). SQLite (.db3) and MCAP both. A recording is written as
# FILE.part and renamed FILE when closed: the killed run's is FILE.part, and nothing is at FILE.
set -u
by=$1; graphs=$2; domain=$3; out=$4
rm -rf "$out"; mkdir -p "$out"
record_and_kill() {  # FILE: a real-clock run recording into it, killed after 4 s; sets killed_ns
  "$by" run "$graphs/real_clock.json" --domain "$domain" --quiet --progress 0 --duration 60 --record "$1" > "$out/run.log" 2>&1 &
  local pid=$!
  sleep 4
  kill -9 "$pid"
  killed_ns=$(date +%s%N)
  wait "$pid" 2> /dev/null
  [ ! -e "$1" ] || { echo "FAIL: a killed run's recording is at $1, not $1.part"; exit 1; }
  [ -s "$1.part" ] || { echo "FAIL: no $1.part"; exit 1; }
}
rec="$out/killed.db3"
record_and_kill "$rec"
python3 - "$rec.part" "$killed_ns" <<'PY' || exit 1
import sqlite3, sys
rec, killed = sys.argv[1], int(sys.argv[2])
n, last = sqlite3.connect(rec).execute("SELECT count(*), max(timestamp) FROM messages").fetchone()
lost = (killed - (last or 0)) / 1e9
print(f"killed after 4 s: {n} samples kept, the last {lost:.2f} s before the kill")
sys.exit(0 if n >= 100 and lost <= 1.5 else 1)
PY
# The same as MCAP: a chunk is written at least once a second; the file has no footer, so bag info
# reads it up to there, says the recording was not closed, and exits 2.
rec="$out/killed.mcap"
record_and_kill "$rec"
"$by" bag info "$rec.part" --json > "$out/info.json" 2> "$out/info.err"; rc=$?
[ $rc -eq 2 ] || { cat "$out/info.err"; echo "FAIL: bag info on a killed run's MCAP: exit $rc, expected 2"; exit 1; }
grep -q "killed.mcap.part: damaged at byte [0-9]*: the file ends without its data section's end and footer: the recording was not closed" "$out/info.err" \
  || { cat "$out/info.err"; echo "FAIL: bag info did not say the recording was not closed"; exit 1; }
python3 - "$out/info.json" "$killed_ns" <<'PY' || exit 1
import json, sys
info, killed = json.load(open(sys.argv[1])), int(sys.argv[2])
lost = (killed - info["end_s"] * 1e9) / 1e9
print(f"MCAP, killed after 4 s: {info['messages']} samples kept, the last {lost:.2f} s before the kill")
sys.exit(0 if info["messages"] >= 100 and lost <= 1.5 else 1)
PY
echo "recording_crash: ok"
