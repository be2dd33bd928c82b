#!/usr/bin/env bash
# The command watchdog: a car whose commands stop (the stack's recorded commands replayed until
# the recording ends, 3 s into a race) releases the throttle and brakes to a stop; with the
# stack's commands flowing it never trips (the race itself, and configs/race.json's own tests).
set -u
by=$1; configs=$2; graphs=$3; domain=$4; out=$5
rm -rf "$out"; mkdir -p "$out"
"$by" run "$configs/race.json" --domain "$domain" --quiet --progress 0 --duration 3 --out "$out/race" --no-report \
  --record "$out/commands.db3" --record-only 'manager.command' > "$out/race.log" 2>&1
python3 - "$out/race/summary.json" <<'PY' || exit 1
import json, sys
car = json.load(open(sys.argv[1]))["nodes"]["car"]["metrics"]
print(f"race, commands flowing: watchdog trips {car['command_watchdog_trips']:.0f}, speed {car['final_speed_mps']:.1f} m/s")
sys.exit(0 if car["command_watchdog_trips"] == 0 and car["final_speed_mps"] > 30 else 1)
PY
"$by" run "$graphs/replay/commands_stop.json" --domain "$domain" --quiet --progress 0 --set commands.file="$out/commands.db3" \
  --out "$out/stop" --no-report > "$out/stop.log" 2>&1 || { cat "$out/stop.log"; echo "FAIL: the replayed run"; exit 1; }
grep -q "no command for 0.2[0-9]* s: throttle off, braking to a stop" "$out/stop.log" || { cat "$out/stop.log"; echo "FAIL: no warning"; exit 1; }
python3 - "$out/stop/summary.json" <<'PY' || exit 1
import json, sys
car = json.load(open(sys.argv[1]))["nodes"]["car"]["metrics"]
print(f"commands stopped at 3 s: watchdog trips {car['command_watchdog_trips']:.0f}, speed at 12 s {car['final_speed_mps']:.2f} m/s")
sys.exit(0 if car["command_watchdog_trips"] == 1 and abs(car["final_speed_mps"]) < 0.5 else 1)
PY
echo "command_watchdog: ok"
