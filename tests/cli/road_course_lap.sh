#!/usr/bin/env bash
# configs/sim_truth_limit.json: the ground-truth driver at the car's limit (lqr, feedforward pedals,
# the vehicle file's envelope) on a road course: 2 laps, no wall contact, no track violation, and
# the flying lap within 1.03 x the lap its speed profile plans (issue 16's target).
#   road_course_lap.sh BRICKYARD GRAPH DOMAIN OUT [run options...]
set -u
by=$1; graph=$2; domain=$3; out=$4; shift 4
rm -rf "$out"
"$by" run "$graph" --domain "$domain" --quiet --no-report --out "$out" "$@"; rc=$?
[ $rc -eq 0 ] || { echo "FAIL: exit $rc"; exit 1; }
python3 - "$out/summary.json" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
r = s["nodes"]["referee"]["metrics"]; d = s["nodes"]["driver"]["metrics"]
laps, planned = r["lap_times_s"], d["planned_lap_s"]
print("laps %s, planned %.2f s, contacts %d, violations %d, least wall clearance %.2f m" %
      (laps, planned, r["wall_contacts"], r["track_violations"], r["min_wall_clearance_m"]))
ok = len(laps) >= 2 and r["wall_contacts"] == 0 and r["track_violations"] == 0 and laps[1] <= 1.03 * planned
print("flying lap %.3f x planned: %s" % (laps[1] / planned if len(laps) > 1 else float("nan"), "ok" if ok else "FAIL"))
sys.exit(0 if ok else 1)
PY
