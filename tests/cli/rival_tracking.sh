#!/usr/bin/env bash
# The tracker against the simulator's truth with a rival in the LiDARs' view (issue 46):
# tests/graphs/rivals/race_rival.json on IMS, the rival from a standstill 60 m ahead at 80 % of its
# line's pace, 40 s, no race (laps 0). sim.tracking_scorer's figures held to what this graph gives
# on the sim clock (docs/tracking.md): the car tracked in both bands it passes through, within
# its bounds there, almost no phantom (a wall's stripe, or a second track on the car), no contact.
# usage: rival_tracking.sh BRICKYARD GRAPHS DOMAIN OUT
set -u
by=$1; graphs=$2; domain=$3; out=$4
rm -rf "$out"
fail() { echo "FAIL: $*"; exit 1; }
"$by" run "$graphs/rivals/race_rival.json" --set referee.laps=0 --duration 40 \
  --domain "$domain" --quiet --progress 0 --no-report --out "$out" > "$out.log" 2>&1 || { tail -3 "$out.log"; fail "the run failed"; }
python3 - "$out/summary.json" <<'PY' || fail "the tracker's figures"
import json, sys
s = json.load(open(sys.argv[1]))["nodes"]
m, r = s["tracking"]["metrics"], s["referee"]["metrics"]
print(json.dumps({k: round(v, 3) for k, v in sorted(m.items())}))
bad = []
def at_most(key, bound):
    if not m.get(key, float("inf")) <= bound: bad.append(f"{key} {m.get(key)} > {bound}")
def at_least(key, bound):
    if not m.get(key, 0) >= bound: bad.append(f"{key} {m.get(key)} < {bound}")
at_least("tracked_30_60", 60); at_least("tracked_60_100", 600)
at_most("missed_30_60", 30); at_most("missed_60_100", 5)
at_most("position_error_p95_m_60_100", 0.6); at_most("relative_error_p95_m_60_100", 0.6)
at_most("position_error_p95_m_30_60", 0.5); at_most("speed_error_p95_mps_60_100", 2.5)
at_most("phantom_tracks", 5)
if r["car_contacts"] != 0: bad.append(f"{r['car_contacts']} contacts")
if bad: sys.exit("; ".join(bad))
PY
echo "rival_tracking: ok"
