#!/usr/bin/env bash
# The issue's case: the main job at 60 m/s, both receivers failing at t = 127 s. Dead reckoning
# drifts past delta during the outage; the fusion must re-acquire (docs/algorithms.md, "Coming
# back") and the race must finish its 2 laps without a wall contact.
#   comes_back.sh BRICKYARD GRAPH DOMAIN OUT
set -u
by=$1; graph=$2; domain=$3; out=$4
rm -rf "$out"
"$by" run "$graph" --domain "$domain" --quiet --no-report --out "$out" --set planner.v_max=60; rc=$?
[ $rc -eq 0 ] || { echo "FAIL: exit $rc"; exit 1; }
python3 - "$out/summary.json" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
e = s["nodes"]["estimator"]["metrics"]; r = s["nodes"]["referee"]["metrics"]
print("reacquisitions %d, laps %s, wall contacts %d" % (e["reacquisitions"], r["lap_times_s"], r["wall_contacts"]))
sys.exit(0 if e["reacquisitions"] >= 1 and r["laps_completed"] >= 2 and r["wall_contacts"] == 0 else 1)
PY
