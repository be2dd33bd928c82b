#!/usr/bin/env bash
# Issue 19's first target, on these machines: the main job split over two processes on the real
# clock (simulator, car stack), the stack killed with SIGKILL mid-race at speed. The car must
# stop on its command watchdog without touching a wall, and the simulator's process must say,
# within the liveliness lease, which input went silent, then fail its run with that reason.
set -u
by=$1; graph=$2; domain=$3; out=$4
rm -rf "$out"; mkdir -p "$out"
"$by" run "$graph" --process sim --domain "$domain" --duration 30 --progress 0 --out "$out/sim" --no-report > "$out/sim.log" 2>&1 &
pid_sim=$!
"$by" run "$graph" --process stack --domain "$domain" --duration 30 --progress 0 --quiet > "$out/stack.log" 2>&1 &
pid_stack=$!
sleep 15
kill -9 $pid_stack
wait $pid_sim; rc=$?
grep "warning\|failed\|no command" "$out/sim.log" | head -5
[ $rc -eq 1 ] || { cat "$out/sim.log"; echo "FAIL: the simulator's process exited $rc"; exit 1; }
python3 - "$out/sim/summary.json" <<'PY' || exit 1
import json, sys
s = json.load(open(sys.argv[1]))
car, ref = s["nodes"]["car"]["metrics"], s["nodes"]["referee"]["metrics"]
lost = s.get("lost_peers", [])
print(f"stack killed at 15 s: top speed {ref['max_speed_mps']:.1f} m/s, watchdog trips {car['command_watchdog_trips']:.0f}, "
      f"speed at the end {car['final_speed_mps']:.2f} m/s, wall contacts {ref['wall_contacts']:.0f}, "
      f"least wall clearance {ref['min_wall_clearance_m']:.2f} m; lost: {lost}")
ok = car["command_watchdog_trips"] >= 1 and abs(car["final_speed_mps"]) < 0.5 and ref["wall_contacts"] == 0
ok = ok and ref["max_speed_mps"] > 30 and any(l.startswith("input car.command: its writer manager.command (process 'stack')") for l in lost)
sys.exit(0 if ok else 1)
PY
echo "stack_killed: ok"
