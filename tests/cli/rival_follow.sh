#!/usr/bin/env bash
# Following a slower car with no way past it planned (issue 46): tests/graphs/rivals/race_rival.json
# on a road course (ARGS: its track, wall side and racing line), the rival from a standstill 60 m
# ahead at 80 % of its line's pace, 90 s, no race (laps 0). The planner takes the tracker's cars:
# their detections are not obstacles, its speeds follow the car in its way. Held: no contact with
# the car or a wall, no track limit broken, the planner followed, the least gap between the cars
# at least MIN_GAP m.
# usage: rival_follow.sh BRICKYARD GRAPHS DOMAIN OUT MIN_GAP ARGS...
set -u
by=$1; graphs=$2; domain=$3; out=$4; min_gap=$5; shift 5
rm -rf "$out"
fail() { echo "FAIL: $*"; exit 1; }
"$by" run "$graphs/rivals/race_rival.json" "$@" --set referee.laps=0 --duration 90 \
  --domain "$domain" --quiet --progress 0 --no-report --out "$out" > "$out.log" 2>&1 || { tail -3 "$out.log"; fail "the run failed"; }
python3 - "$out/summary.json" "$min_gap" <<'PY' || fail "the follow"
import json, sys
s = json.load(open(sys.argv[1]))["nodes"]
r, p = s["referee"]["metrics"], s["planner"]["metrics"]
print(f"contacts {r['car_contacts']:.0f}, walls {r['wall_contacts']:.0f}, track limits {r['track_violations']:.0f}, "
      f"least gap {r['min_car_gap_m']:.1f} m, plans following {p['plans_following']:.0f} of {p['plans']:.0f}, "
      f"least bumper gap planned from {p['min_follow_gap_m']:.1f} m")
bad = []
if r["car_contacts"] or r["wall_contacts"] or r["track_violations"]: bad.append("a contact or a track limit broken")
if not r["min_car_gap_m"] >= float(sys.argv[2]): bad.append(f"least gap {r['min_car_gap_m']:.1f} m < {sys.argv[2]} m")
if not p["plans_following"] > 0: bad.append("the planner never followed the car")
if bad: sys.exit("; ".join(bad))
PY
echo "rival_follow: ok"
