#!/usr/bin/env bash
# Ctrl-C on a real-clock run with no end: a clean shutdown, exit 0, result "interrupted", and the
# sinks' metrics in the summary (they were deactivated).
set -u
by=$1; graph=$2; domain=$3; out=$4
rm -rf "$out"
"$by" run "$graph" --one-process --domain "$domain" --out "$out" --set check.min_count=0 &
pid=$!
sleep 1.5
kill -INT $pid
wait $pid; rc=$?
echo "exit code $rc"
[ $rc -eq 0 ] || { echo "FAIL: exit code"; exit 1; }
grep -q '"result": "interrupted"' "$out/summary.json" || { echo "FAIL: result"; exit 1; }
grep -q '"passed": 1.0' "$out/summary.json" || { echo "FAIL: sink not deactivated"; exit 1; }
echo "clean shutdown on SIGINT"
