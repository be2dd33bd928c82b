#!/usr/bin/env bash
# The main job, configs/ims_race.json, as scripts/demo runs it: two laps, no wall contact, every
# pylon passed at least 1 m off, the wall follower in and out, a report written.
set -u
by=$1; graph=$2; domain=$3; out=$4; shift 4  # then more options for the run (--seed N)
rm -rf "$out"
"$by" run "$graph" --domain "$domain" --quiet --out "$out" "$@" > "$out.log" 2>&1; rc=$?
[ $rc -eq 0 ] || { tail -5 "$out.log"; echo "FAIL: exit $rc"; exit 1; }
python3 - "$out/summary.json" <<'PY' || exit 1
import json, sys
s = json.load(open(sys.argv[1]))
r, m = s["nodes"]["referee"]["metrics"], s["nodes"]["manager"]["metrics"]
checks = {
    "two laps": r["laps_completed"] == 2,
    "no wall contact": r["wall_contacts"] == 0,
    "no track violation": r["track_violations"] == 0,
    "no pylon hit": r["obstacles_hit"] == 0,
    "pylons passed >= 1 m off": r["obstacle_min_clearance_m"] is not None and r["obstacle_min_clearance_m"] >= 1.0,
    "wall follower in and out": m["entered_WALL_FOLLOW"] == 1 and m["entered_PATH"] == 1,
}
print(f"laps {r['lap_times_s']}, pylon clearance {r['obstacle_min_clearance_m']:.2f} m, wall clearance {r['min_wall_clearance_m']:.2f} m, "
      f"localization max error {r['localization_max_error_m']:.2f} m, wall follower {m['time_s_WALL_FOLLOW']:.1f} s")
bad = [k for k, ok in checks.items() if not ok]
print("FAIL: " + ", ".join(bad) if bad else "main job: ok")
sys.exit(1 if bad else 0)
PY
[ -s "$out/report.html" ] || { echo "FAIL: no report"; exit 1; }
