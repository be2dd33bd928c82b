#!/usr/bin/env bash
# Racing on the map through a GNSS outage (issue 41): the track mapped by a mapping drive
# (scripts/track-map, the map cached under OUT/map), then configs/race_on_map.json with both
# receivers gone (dropout) from FAULT_START to FAULT_END: 2 laps, no wall contact, no track
# violation, never on the wall follower (the map localizer's poses keep the path), the lap with
# the outage within 1.03 x the planned lap, the map's poses taken by the fusion throughout.
#   race_on_map.sh BRICKYARD GRAPH DOMAIN OUT TRACK FAULT_START FAULT_END [--arg NAME=VALUE]...
set -u
by=$1; graph=$2; domain=$3; out=$4; track=$5; start=$6; end=$7; shift 7
root=$(cd "$(dirname "$0")/../.." && pwd)
rm -rf "$out/race"; mkdir -p "$out"
BY=$by "$root/scripts/track-map" "$track" "$out/map" "$@" || { echo "FAIL: the mapping drive"; exit 1; }
dropout="[{\"type\":\"dropout\",\"start_s\":$start,\"end_s\":$end}]"
"$by" run "$graph" --domain "$domain" --quiet --no-report --out "$out/race" --arg track="$track" "$@" \
  --arg map_file="$out/map/map.pcd" --set gnss_left.faults="$dropout" --set gnss_right.faults="$dropout"; rc=$?
[ $rc -eq 0 ] || { echo "FAIL: exit $rc"; exit 1; }
python3 - "$out/race/summary.json" "$start" "$end" <<'PY'
import json, sys
s = json.load(open(sys.argv[1])); start, end = float(sys.argv[2]), float(sys.argv[3])
n = s["nodes"]; r = n["referee"]["metrics"]; p = n["planner"]["metrics"]; m = n["manager"]["metrics"]
e = n["estimator"]["metrics"]; loc = n["map_localizer"]["metrics"]
laps, planned = r["lap_times_s"], p["planned_lap_s"]
print("laps %s, planned %.2f s, contacts %d, violations %d, least wall clearance %.2f m, wall following %.1f s, final mode %s"
      % (laps, planned, r["wall_contacts"], r["track_violations"], r["min_wall_clearance_m"], m["time_s_WALL_FOLLOW"], m["final_mode"]))
print("map: %d of %d frames located (%d with an unseen direction), correction max %.2f m; fusion took %d map poses, refused %d"
      % (loc["located"], loc["frames"], loc["located_with_unseen_direction"], loc["correction_max_m"], e["scan_updates"], e["scan_refused"]))
worst = max(laps[1:]) / planned if len(laps) > 1 else float("nan")
ok = (len(laps) >= 2 and r["wall_contacts"] == 0 and r["track_violations"] == 0 and m["entered_WALL_FOLLOW"] == 0
      and m["final_mode"] == "PATH" and worst <= 1.03 and e["scan_updates"] > 0)
print("the outage %.0f s to %.0f s; slowest flying lap %.3f x planned: %s" % (start, end, worst, "ok" if ok else "FAIL"))
sys.exit(0 if ok else 1)
PY
