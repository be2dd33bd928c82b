#!/usr/bin/env bash
# A rival far ahead at our pace (tests/graphs/rivals/rival_ahead.json, issue 46): 30 s, no race
# (laps 0): the run succeeds, the referee counts no contact with it and reports the least gap.
# usage: rival_no_contact.sh BRICKYARD GRAPHS DOMAIN OUT
set -u
by=$1; graphs=$2; domain=$3; out=$4
rm -rf "$out"
fail() { echo "FAIL: $*"; exit 1; }
"$by" run "$graphs/rivals/rival_ahead.json" --arg rival_start_s=1200 --arg rival_scale=1.0 --set referee.laps=0 --duration 30 \
  --domain "$domain" --quiet --progress 0 --out "$out" > "$out.log" 2>&1 || { tail -3 "$out.log"; fail "the run failed"; }
python3 - "$out/summary.json" <<'PY' || fail "the referee's figures of the rival"
import json, sys
m = json.load(open(sys.argv[1]))["nodes"]["referee"]["metrics"]
if m["car_contacts"] != 0: sys.exit(f"{m['car_contacts']} contacts with a rival 1200 m ahead at our pace")
if not 50 < m["min_car_gap_m"] < 1e6: sys.exit(f"least gap {m['min_car_gap_m']}")
print(f"no contact, least gap {m['min_car_gap_m']:.0f} m")
PY
echo "rival_no_contact: ok"
