#!/usr/bin/env bash
# A ROS 2 bag of a team's own played onto Brickyard's wires (issue 45, docs/ros2.md): 3 s of the
# main job recorded (the LiDARs' clouds, the two receivers' fixes, the IMU), made into a rosbag2
# MCAP by third-party libraries (tests/clients/ros2_bag_write.cjs: PointCloud2, NavSatFix with
# latitude and longitude from tests/cli/enu_to_geodetic.py, Imu; ROS 2 Humble's definitions), and
# played by `bag play --map` while `topic echo` reads the wires: each sample read equals the
# recording's (the clouds' points exactly, the IMU exactly, a fix's position within 1 mm after
# latitude and longitude and back). The bag's topics not in the map are listed as not played.
# Bad input, each exit 2 named: a topic the bag lacks, a wire not NODE.PORT, a NavSatFix without
# a datum, a type bag play does not convert, a PointCloud2 without z, a ROS 2 bag without --map;
# a sample cut short is counted, named and skipped.
# Then the same drive in-process, through the perception and the fusion (the replay.ros2_* plugins
# beside the replay of the recording): the same obstacles and walls frame by frame, the fusion's
# track within 1 cm.
# usage: ros2_bag_play.sh BRICKYARD CLIENTS RACE_GRAPH DOMAIN OUT
set -u
by=$1; clients=$2; race=$3; domain=$4; out=$5
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$out"; mkdir -p "$out"
fail() { echo "FAIL: $*"; exit 1; }
"$by" run "$race" --domain "$domain" --duration 10 --seed 3 --quiet --progress 0 --no-report \
  --record "$out/src.mcap" --record-only 'lidar_*.cloud,gnss_*.fix,imu.imu,wheels.speeds,estimator.estimate' > "$out/src.log" 2>&1
# 10 s of a two-lap race: it ends at its duration, the laps not done (said so), and nothing else.
grep -q "did not finish: 0 of 2 laps.*(sim 10\.0" "$out/src.log" && [ -s "$out/src.mcap" ] || { tail -5 "$out/src.log"; fail "recording the source"; }
node "$clients/mcap_dump.cjs" "$out/src.mcap" gnss_left.fix gnss_right.fix > "$out/fixes.jsonl" || fail "reading the fixes"
python3 "$here/enu_to_geodetic.py" 39.7930 -86.2389 220.0 "$out/fixes.jsonl" "$out/fixes_ll.json" || fail "latitude and longitude"
node "$clients/ros2_bag_write.cjs" "$out/src.mcap" "$out/fixes_ll.json" "$out/bag.mcap" > "$out/written.json" || fail "writing the ROS 2 bag"
echo "the ROS 2 bag (third-party written): $(cat "$out/written.json")"

map() {  # map FILE [extra python edits]: the map of the bag's topics onto the race's wires
  python3 - "$1" "${2:-}" <<'PY'
import json, sys
m = {"topics": {"/lidar_front/points": {"wire": "lidar_front.cloud", "sensor_id": 0, "mount": {"x": 1.5, "z": 1.1}},
                "/gnss_left/fix": {"wire": "gnss_left.fix", "receiver_id": 0},
                "/gnss_right/fix": {"wire": "gnss_right.fix", "receiver_id": 1},
                "/imu/data": {"wire": "imu.imu"},
                "/odom": {"wire": "estimator.estimate"}},
     "datum": {"latitude": 39.7930, "longitude": -86.2389, "altitude": 220.0}}
exec(sys.argv[2])
json.dump(m, open(sys.argv[1], "w"))
PY
}
refused() {  # refused NAME PATTERN BAG play-args...: exit 2 and the pattern said
  local name=$1 pattern=$2; shift 2
  "$by" bag play "$@" --domain "$domain" > "$out/$name.log" 2>&1; local rc=$?
  [ $rc = 2 ] && grep -q -- "$pattern" "$out/$name.log" || { cat "$out/$name.log"; fail "$name: exit $rc, or not said: $pattern"; }
}
map "$out/map.json"
map "$out/lacks.json" 'm["topics"]["/lidar_rear/points"] = {"wire": "lidar_rear.cloud"}'
refused lacks "lacks.json#/topics/~1lidar_rear~1points: the bag .*bag.mcap has no topic /lidar_rear/points (its topics: " "$out/bag.mcap" --map "$out/lacks.json"
map "$out/wire.json" 'm["topics"]["/imu/data"]["wire"] = "imu"'
refused wire 'wire.json#/topics/~1imu~1data/wire: expected "NODE.PORT", found "imu"' "$out/bag.mcap" --map "$out/wire.json"
map "$out/datum.json" 'del m["datum"]'
refused datum "datum.json#/datum: missing: /gnss_left/fix is a NavSatFix" "$out/bag.mcap" --map "$out/datum.json"
map "$out/string.json" 'm["topics"]["/rosout_text"] = {"wire": "log.text"}'
refused string "/rosout_text holds std_msgs/msg/String, which bag play does not convert" "$out/bag.mcap" --map "$out/string.json"
map "$out/bad_cloud.json" 'm["topics"] = {"/bad/points": {"wire": "lidar_front.cloud"}}'
refused bad_cloud "sample 0 of /bad/points: PointCloud2: no field 'z' (fields: x, y, intensity)" "$out/bag.mcap" --map "$out/bad_cloud.json"
refused no_map "not a brickyard recording" "$out/bag.mcap"
map "$out/key.json" 'm["topics"]["/imu/data"]["frame"] = "imu_link"'
refused key 'key.json#/topics/~1imu~1data/frame: not a key here (keys: mount, receiver_id, sensor_id, wire)' "$out/bag.mcap" --map "$out/key.json"
map "$out/range.json" 'm["datum"]["latitude"] = 95'
refused range 'range.json#/datum/latitude: expected -90.0 to 90.0, found 95' "$out/bag.mcap" --map "$out/range.json"
echo '{"topics": ' > "$out/not_json.json"
refused not_json "not_json.json: not JSON" "$out/bag.mcap" --map "$out/not_json.json"
# A message whose bytes end early: counted, the first named, skipped; the others played.
map "$out/damaged.json" 'm["topics"] = {"/imu/damaged": {"wire": "imu.imu"}}'
"$by" bag play "$out/bag.mcap" --map "$out/damaged.json" --domain "$domain" --rate 100 > "$out/damaged.log" 2>&1 || { cat "$out/damaged.log"; fail "a damaged sample: exit $?"; }
grep -q "bag play: 1 damaged samples of /imu/damaged skipped (the first: sample 4 of /imu/damaged: Imu: .* runs past the sample's 20 bytes)" "$out/damaged.log" \
  && grep -q "bag play: 9 samples of 1 topics" "$out/damaged.log" || { cat "$out/damaged.log"; fail "the damaged sample not counted, named and skipped"; }
# The same in-process: replay.ros2_imu skips it, says so and counts it.
python3 -c "import json,sys; json.dump({'name': 'damaged', 'nodes': {'imu': {'plugin': 'replay.ros2_imu', 'params': {'file': sys.argv[2], 'topic': '/imu/damaged', 'retime_from_ns': 0}}},
  'wires': [], 'clock': {'mode': 'sim', 'step_s': 0.002, 'duration_s': 2}}, open(sys.argv[1], 'w'))" "$out/damaged_graph.json" "$out/bag.mcap"
"$by" run "$out/damaged_graph.json" --domain "$domain" --progress 0 --no-report --out "$out/damaged_run" > "$out/damaged_run.log" 2>&1 || { tail -3 "$out/damaged_run.log"; fail "replay.ros2_imu of a damaged sample"; }
grep -q "sample 4 of '/imu/damaged' is damaged, skipped: Imu: .* runs past the sample's 20 bytes" "$out/damaged_run.log" \
  && python3 -c "import json,sys; m=json.load(open(sys.argv[1]))['nodes']['imu']['metrics']; sys.exit(0 if (m['damaged_skipped'], m['replayed']) == (1, 9) else 1)" "$out/damaged_run/summary.json" \
  || { cat "$out/damaged_run.log"; fail "replay.ros2_imu did not skip, say and count the damaged sample"; }

"$by" topic echo gnss_left.fix --domain "$domain" --count 30 --duration 25 > "$out/echo_fix.jsonl" 2> "$out/echo_fix.log" &
e1=$!
"$by" topic echo imu.imu --domain "$domain" --count 100 --duration 25 > "$out/echo_imu.jsonl" 2> "$out/echo_imu.log" &
e2=$!
"$by" topic echo lidar_front.cloud --domain "$domain" --count 3 --duration 25 > "$out/echo_cloud.jsonl" 2> "$out/echo_cloud.log" &
e3=$!
"$by" topic echo estimator.estimate --domain "$domain" --count 100 --duration 25 > "$out/echo_odom.jsonl" 2> "$out/echo_odom.log" &
e4=$!
sleep 1
"$by" bag play "$out/bag.mcap" --map "$out/map.json" --domain "$domain" > "$out/play.log" 2>&1 || { cat "$out/play.log"; fail "bag play --map"; }
wait $e1 && wait $e2 && wait $e3 && wait $e4 || { tail -3 "$out"/echo_*.log; fail "topic echo did not read the played wires"; }
cat "$out/play.log"
grep -q "not in the map, not played: .*/bad/points (sensor_msgs/msg/PointCloud2).*/rosout_text (std_msgs/msg/String)" "$out/play.log" \
  || fail "the bag's unmapped topics were not said"
node "$clients/mcap_dump.cjs" "$out/src.mcap" gnss_left.fix imu.imu lidar_front.cloud estimator.estimate > "$out/src.jsonl" || fail "reading the source"
python3 - "$out" <<'PY' || fail "the played samples are not the recording's"
import json, math, sys
out = sys.argv[1]
src = {}
for line in open(f"{out}/src.jsonl"):
    r = json.loads(line)
    src[(r["topic"], r["msg"]["header"]["stamp_ns"])] = r["msg"]
def same_estimate(topic, g, want):  # a team's odometry: the pose through a quaternion, the rest as it was
    for k in ("x", "y", "speed", "yaw_rate"):
        if g[k] != want[k]: sys.exit(f"{topic}: {k} {g[k]} against {want[k]}")
    if abs(math.remainder(g["yaw"] - want["yaw"], 2 * math.pi)) > 1e-12: sys.exit(f"{topic}: yaw {g['yaw']} against {want['yaw']}")
    if g["covariance"] != want["covariance"]: sys.exit(f"{topic}: covariance {g['covariance']} against {want['covariance']}")
for topic, name in (("gnss_left.fix", "fix"), ("imu.imu", "imu"), ("lidar_front.cloud", "cloud"), ("estimator.estimate", "odom")):
    got = [json.loads(l) for l in open(f"{out}/echo_{name}.jsonl") if l.strip()]
    if not got: sys.exit(f"{topic}: nothing read")
    worst = 0.0
    for g in got:
        want = src.get((topic, g["header"]["stamp_ns"]))
        if want is None: sys.exit(f"{topic}: a sample stamped {g['header']['stamp_ns']} is not the recording's")
        if name == "fix":
            err = max(abs(g[k] - want[k]) for k in ("x", "y", "z"))
            if err > 1e-3: sys.exit(f"{topic}: a fix {err:.6f} m from the recording's")
            worst = max(worst, err)
            if (g["fix_type"], g["valid"]) != (want["fix_type"], want["valid"]) and not (want["fix_type"] in (1, 2) and g["fix_type"] == 1):
                sys.exit(f"{topic}: fix_type {g['fix_type']} valid {g['valid']} against {want['fix_type']} {want['valid']}")
        elif name == "odom":
            same_estimate(topic, g, want)
        elif name == "imu":
            for k in ("accel_x", "accel_y", "accel_z", "gyro_x", "gyro_y", "gyro_z"):
                if g[k] != want[k]: sys.exit(f"{topic}: {k} {g[k]} against {want[k]}")
        else:
            for k in ("x", "y", "z", "intensity"):
                if g[k] != want[k]: sys.exit(f"{topic}: the points' {k} differ")
            if (g["sensor_x"], g["sensor_z"]) != (1.5, 1.1): sys.exit(f"{topic}: the mount is not the map's")
    print(f"{topic}: {len(got)} samples read from the played bag, each the recording's" + (f" (positions within {worst:.1e} m)" if name == "fix" else ""))
PY

# A team's odometry in-process: replay.ros2_odometry gives every estimate back, as bag play did.
python3 -c "import json,sys; json.dump({'name': 'odometry', 'nodes': {'odom': {'plugin': 'replay.ros2_odometry', 'params': {'file': sys.argv[2], 'topic': '/odom', 'retime_from_ns': 0}}},
  'wires': [], 'clock': {'mode': 'sim', 'duration_s': 10.5}}, open(sys.argv[1], 'w'))" "$out/odom_graph.json" "$out/bag.mcap"
"$by" run "$out/odom_graph.json" --domain "$domain" --progress 0 --no-report --record "$out/odom.mcap" > "$out/odom_run.log" 2>&1 \
  || { tail -3 "$out/odom_run.log"; fail "replay.ros2_odometry"; }
node "$clients/mcap_dump.cjs" "$out/odom.mcap" odom.out > "$out/odom.jsonl" || fail "reading the odometry replayed"
python3 - "$out" <<'PY' || fail "replay.ros2_odometry's estimates are not the recording's"
import json, math, sys
out = sys.argv[1]
src = [json.loads(l)["msg"] for l in open(f"{out}/src.jsonl") if json.loads(l)["topic"] == "estimator.estimate"]
got = [json.loads(l)["msg"] for l in open(f"{out}/odom.jsonl")]
if len(got) != len(src) or not got: sys.exit(f"{len(got)} estimates replayed, {len(src)} recorded")
for g, w in zip(got, src):
    if (g["x"], g["y"], g["speed"], g["yaw_rate"], g["covariance"]) != (w["x"], w["y"], w["speed"], w["yaw_rate"], w["covariance"]) \
       or abs(math.remainder(g["yaw"] - w["yaw"], 2 * math.pi)) > 1e-12 or g["header"]["stamp_ns"] != w["header"]["stamp_ns"]:
        sys.exit(f"an estimate replayed differs: {g} against {w}")
print(f"replay.ros2_odometry: {len(got)} estimates from the bag's /odom, each the recording's")
PY

# The same drive through the perception and the fusion in-process: from the recording, and from the
# ROS 2 bag by the replay.ros2_* plugins (the clouds' mounts, which ROS 2's cloud does not carry,
# from the recording's first cloud of each LiDAR; the wheel speeds from the recording in both).
graphs=$(dirname "$race")/../tests/graphs/replay
node "$clients/mcap_dump.cjs" "$out/src.mcap" --first lidar_front.cloud lidar_left.cloud lidar_right.cloud > "$out/mounts.jsonl" || fail "the mounts"
mounts=$(python3 -c "
import json, sys
for line in open(sys.argv[1]):
    r = json.loads(line); n = r['topic'].split('.')[0]; m = r['msg']
    for k in ('x', 'y', 'z', 'roll', 'pitch', 'yaw'): print(f'--arg {n}_mount_{k}={m[\"sensor_\" + k]!r}', end=' ')
" "$out/mounts.jsonl")
keep='estimator.estimate,obstacles.obstacles,wall_left.wall,wall_right.wall'
"$by" run "$graphs/perception_fusion_from_recording.json" --domain "$domain" --quiet --progress 0 --no-report --arg recording="$out/src.mcap" \
  --arg duration=10 --record "$out/from_recording.mcap" --record-only "$keep" > "$out/from_recording.log" 2>&1 || { tail -3 "$out/from_recording.log"; fail "the replay of the recording"; }
"$by" run "$graphs/perception_fusion_from_ros2_bag.json" --domain "$domain" --quiet --progress 0 --no-report --arg recording="$out/src.mcap" \
  --arg bag="$out/bag.mcap" --arg duration=10 $mounts --record "$out/from_bag.mcap" --record-only "$keep" > "$out/from_bag.log" 2>&1 \
  || { tail -3 "$out/from_bag.log"; fail "the replay of the ROS 2 bag"; }
for f in from_recording from_bag; do
  node "$clients/mcap_dump.cjs" "$out/$f.mcap" ${keep//,/ } > "$out/$f.jsonl" || fail "reading $f.mcap"
done
python3 - "$out" <<'PY' || fail "the ROS 2 bag's drive is not the recording's through the perception and the fusion"
import json, math, sys
out = sys.argv[1]
def load(f):
    by = {}
    for line in open(f"{out}/{f}.jsonl"):
        if line.strip():
            r = json.loads(line); by.setdefault(r["topic"], []).append(r["msg"])
    return by
a, b = load("from_recording"), load("from_bag")
for topic in ("obstacles.obstacles", "wall_left.wall", "wall_right.wall"):
    if len(a.get(topic, [])) < 10: sys.exit(f"{topic}: {len(a.get(topic, []))} frames from the recording: too few to judge")
    if a[topic] != b.get(topic): sys.exit(f"{topic}: {len(b.get(topic, []))} frames from the bag, {len(a[topic])} from the recording, or other values")
ea, eb = a["estimator.estimate"], b.get("estimator.estimate", [])
if len(ea) != len(eb) or len(ea) < 100: sys.exit(f"estimator.estimate: {len(eb)} estimates from the bag, {len(ea)} from the recording")
worst = max(math.hypot(p["x"] - q["x"], p["y"] - q["y"]) for p, q in zip(ea, eb))
if worst > 0.01: sys.exit(f"estimator.estimate: the tracks {worst:.4f} m apart")
print(f"through the perception and the fusion: {len(a['obstacles.obstacles'])} obstacle frames and {len(a['wall_left.wall'])} + "
      f"{len(a['wall_right.wall'])} wall frames the same, {len(ea)} estimates within {worst:.1e} m")
PY
echo "ros2_bag_play: ok"
