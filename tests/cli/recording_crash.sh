#!/usr/bin/env bash
# A run killed mid-way (SIGKILL: no handler, no close) keeps its recording up to its last second:
# samples are committed at least once a second, not only every 2000 (a slow run killed at 4 s
# had committed none of its 150 samples).
set -u
by=$1; graphs=$2; domain=$3; out=$4
rm -rf "$out"; mkdir -p "$out"
rec="$out/killed.db3"
"$by" run "$graphs/real_clock.json" --domain "$domain" --quiet --progress 0 --duration 60 --record "$rec" > "$out/run.log" 2>&1 &
pid=$!
sleep 4
kill -9 "$pid"
killed_ns=$(date +%s%N)
wait "$pid" 2> /dev/null
python3 - "$rec" "$killed_ns" <<'PY' || exit 1
import sqlite3, sys
rec, killed = sys.argv[1], int(sys.argv[2])
n, last = sqlite3.connect(rec).execute("SELECT count(*), max(timestamp) FROM messages").fetchone()
lost = (killed - (last or 0)) / 1e9
print(f"killed after 4 s: {n} samples kept, the last {lost:.2f} s before the kill")
sys.exit(0 if n >= 100 and lost <= 1.5 else 1)
PY
echo "recording_crash: ok"
