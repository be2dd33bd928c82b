#!/usr/bin/env bash
# Issues 42 and 43: the car stack on its own wires (configs/car.json, no simulator plugin) against
# the car's hardware simulated in another process (configs/sim_hardware.json), both on the real
# clock, sharing nothing but UDP datagrams on loopback: NovAtel OEM7 logs, Ouster lidar packets, and CAN frames in
# cannelloni datagrams (docs/car-on-wires.md).
#   race: the laps within 1 % of tests/graphs/car_direct.json's (the same stack wired straight to
#         the simulator in one process, sim clock, the same arguments), no contact, no command
#         timeout on either side of the bus, no frame refused, the three LiDARs' frames whole at
#         their 10 Hz.
#   kill: configs/car_split.json (the car's hardware, its drivers and vehicle interface, in a process
#         of its own) and its stack's process killed (SIGKILL) at full speed on the straight (as the
#         car crosses the line after lap 1): the vehicle interface stops the car along the last
#         path, then stops the heartbeat, and the simulated drive-by-wire holds the car; no
#         contact, the car stands, its stop printed.
# usage: car_on_wires.sh BY CONFIGS DIRECT DOMAIN OUT race|kill [TRACK_ARG...] [-- SIM_ARG...]
#   TRACK_ARG: NAME=VALUE given to every graph (the track); SIM_ARG: to the simulator and the
#   direct graph only (walls, fault, laps).
set -u
by=$1; configs=$2; direct=$3; domain=$4; out=$5; mode=$6; shift 6
car_args=(); sim_args=(); side=car
for a in "$@"; do
  if [ "$a" = -- ]; then side=sim; continue; fi
  sim_args+=(--arg "$a")
  [ $side = car ] && car_args+=(--arg "$a")
done
rm -rf "$out"; mkdir -p "$out"

# The car first: it holds the car until race control is heard, and the simulator's drive-by-wire
# brakes if no command comes within 2 s of its start.
car_graph=$configs/car.json
[ "$mode" = kill ] && car_graph=$configs/car_split.json
"$by" run "$car_graph" "${car_args[@]}" --domain "$domain" --out "$out/car" --no-report --progress 0 \
  > "$out/car.log" 2>&1 &
pid_car=$!
# (a split car's processes say it prefixed by their names: "[stack] [brickyard] running")
for _ in $(seq 100); do grep -q "^\(\[[a-z]*\] \)\?\[brickyard\] running" "$out/car.log" && break; sleep 0.1; done
grep -q "^\(\[[a-z]*\] \)\?\[brickyard\] running" "$out/car.log" || { cat "$out/car.log"; echo "FAIL: the car's process did not start"; exit 1; }
# Ready as a team waits for its car before the green: the planner's road graph built (it takes
# it the first second or so of its run; on the sim clock the direct graph's time stands still
# meanwhile, so a simulator started before would cost lap 1 that second, the car held).
for _ in $(seq 300); do grep -q "info planner: road graph built" "$out/car.log" && break; sleep 0.1; done
grep -q "info planner: road graph built" "$out/car.log" || { cat "$out/car.log"; echo "FAIL: the car's planner was not ready within 30 s"; exit 1; }

if [ "$mode" = kill ]; then
  # The stack's process killed as the car crosses the line after its first lap, at full speed. The
  # car's hardware process (its drivers and vehicle interface, configs/car_split.json) lives on: the
  # interface stops the car along the last path, then stops the heartbeat, and the simulated
  # drive-by-wire holds the car.
  "$by" run "$configs/sim_hardware.json" "${sim_args[@]}" --domain $((domain + 1)) --duration 90 --out "$out/sim" \
    --no-report --progress 0 > "$out/sim.log" 2>&1 &
  pid_sim=$!
  for _ in $(seq 1200); do grep -q "info referee: lap 1:" "$out/sim.log" && break; sleep 0.1; done
  pkill -9 -f -- "$car_graph --process stack --domain $domain " || { echo "FAIL: no stack process to kill"; kill $pid_car $pid_sim; exit 1; }
  wait $pid_sim
  kill -INT $pid_car; wait $pid_car
  grep "vehicle: commands\|drive-by-wire\|referee" "$out/car.log" "$out/sim.log" | grep -v "referee  " | head -8
  python3 - "$out/sim/summary.json" "$out/car/hardware/summary.json" <<'PY' || exit 1
import json, sys
n = json.load(open(sys.argv[1]))["nodes"]
vi = json.load(open(sys.argv[2]))["nodes"]["vehicle"]["metrics"]
dbw, car, ref = n["dbw"]["metrics"], n["car"]["metrics"], n["referee"]["metrics"]
print(f"the stack's process killed at the line after lap 1: top speed {ref['max_speed_mps']:.1f} m/s; the vehicle interface's stop "
      f"along the path in {vi.get('stop_distance_m', float('nan')):.1f} m (stops along the path {vi['path_stops']:.0f}, on the held "
      f"wheel {vi['held_stops']:.0f}, handed over {vi['handed_over']:.0f}); the drive-by-wire's heartbeat losses "
      f"{dbw['heartbeat_losses']:.0f}; speed at the end {car['final_speed_mps']:.2f} m/s; wall contacts {ref['wall_contacts']:.0f}, "
      f"least clearance {ref['min_wall_clearance_m']:.2f} m")
ok = vi["path_stops"] == 1 and vi["held_stops"] == 0 and vi["handed_over"] == 1 and dbw["heartbeat_losses"] >= 1
ok = ok and ref["max_speed_mps"] > 60 and abs(car["final_speed_mps"]) < 0.5 and ref["wall_contacts"] == 0
ok = ok and car["command_watchdog_trips"] == 0
sys.exit(0 if ok else 1)
PY
  echo "car_on_wires kill: ok"
  exit 0
fi

"$by" run "$configs/sim_hardware.json" "${sim_args[@]}" --domain $((domain + 1)) --out "$out/sim" --no-report --progress 0 \
  > "$out/sim.log" 2>&1
rc_sim=$?
kill -INT $pid_car; wait $pid_car
"$by" run "$direct" "${sim_args[@]}" --domain $((domain + 2)) --out "$out/direct" --no-report --quiet > "$out/direct.log" 2>&1
rc_direct=$?
tail -1 "$out/sim.log"; tail -1 "$out/direct.log"
[ $rc_sim -eq 0 ] || { tail -30 "$out/sim.log"; echo "FAIL: the simulator's process exited $rc_sim"; exit 1; }
[ $rc_direct -eq 0 ] || { tail -30 "$out/direct.log"; echo "FAIL: the direct graph exited $rc_direct"; exit 1; }
python3 - "$out" <<'PY' || exit 1
import json, sys
d = sys.argv[1]
sim, car, direct = (json.load(open(f"{d}/{p}/summary.json"))["nodes"] for p in ("sim", "car", "direct"))
laps, ref = sim["referee"]["metrics"]["lap_times_s"], direct["referee"]["metrics"]["lap_times_s"]
worst = max(abs(a / b - 1) for a, b in zip(laps, ref))
dbw, vi = sim["dbw"]["metrics"], car["vehicle"]["metrics"]
delay = max(car[g]["metrics"]["stamp_delay_s_p99"] for g in ("gnss_left", "gnss_right"))
wire = max(car[g]["metrics"]["wire_to_message_s_p99"] for g in ("gnss_left", "gnss_right"))
lidar = max(car[g]["metrics"].get("wire_to_message_s_p99", float("nan")) for g in ("lidar_front", "lidar_left", "lidar_right"))
frames = min(car[g]["metrics"]["frames_complete"] for g in ("lidar_front", "lidar_left", "lidar_right"))
broken = sum(car[g]["metrics"]["frames_incomplete"] for g in ("lidar_front", "lidar_left", "lidar_right"))
refused = sum(v for k, v in vi.items() if k.endswith("_bad")) + vi["bus_datagrams_refused"] + dbw["bad_frames"]
print(f"laps {', '.join(f'{a:.2f}' for a in laps)} s on the wires; {', '.join(f'{b:.2f}' for b in ref)} s direct "
      f"(worst {100 * worst:.2f} %); wall contacts {sim['referee']['metrics']['wall_contacts']:.0f}, least clearance "
      f"{sim['referee']['metrics']['min_wall_clearance_m']:.2f} m; drive-by-wire timeouts {dbw['timeouts']:.0f}, the "
      f"interface's watchdog trips {vi['watchdog_trips']:.0f}, frames refused {refused:.0f}; fixes rejected "
      f"{car['estimator']['metrics']['fixes_rejected']:.0f} (direct {direct['estimator']['metrics']['fixes_rejected']:.0f}); "
      f"the receivers' stamp delay p99 {1000 * delay:.2f} ms, their drivers' wire to message p99 {1000 * wire:.2f} ms; "
      f"LiDAR frames whole {frames:.0f} a sensor at least, broken {broken:.0f}, their drivers' wire to message p99 {1000 * lidar:.2f} ms; "
      f"estimates carried to their step's time by at most {1000 * car['estimator']['metrics']['estimate_carried_max_s']:.1f} ms; "
      f"the command gap at most {1000 * vi['longest_command_gap_s']:.0f} ms")
ok = len(laps) == len(ref) and worst <= 0.01 and sim["referee"]["metrics"]["wall_contacts"] == 0
ok = ok and dbw["timeouts"] == 0 and vi["watchdog_trips"] == 0 and refused == 0
# The LiDARs heard: ten whole frames a second from each for the race (a few lost at its ends).
race_s = json.load(open(f"{d}/sim/summary.json"))["sim_time_s"]
ok = ok and frames >= 9.5 * race_s
sys.exit(0 if ok else 1)
PY
echo "car_on_wires race: ok"
