#!/usr/bin/env bash
# The car in ROS 2's standard messages (ros2.bridge, configs/race_ros2.json; docs/ros2.md): the
# main job, 3 s on the sim clock with the bridge, recorded in MCAP's ros2 profile and in ours with
# the same seed, two pylons ahead. A third party's libraries with ROS 2 Humble's own definitions
# (tests/clients/ros2_bridge_check.cjs) read every bridge message (Odometry, PoseStamped, tf,
# PointCloud2, MarkerArray, Imu, NavSatFix) and find it made of what it came from in the same
# recording (a fix's latitude and longitude against tests/cli/enu_to_geodetic.py's, no GeographicLib); the
# two profiles hold every message equal (ros2_bag_check.cjs: our IDL of ROS 2's types decodes as
# ROS 2's definitions do); `bag info` names the types. Then live, on the real clock: `topic echo`
# reads the bridge's odometry off the wire under ROS 2's names. A bridge output's type changed, or
# a gnss input wired with no datum, is refused (exit 2, named).
# usage: ros2_bridge.sh BRICKYARD CLIENTS CONFIGS DOMAIN OUT
set -u
by=$1; clients=$2; configs=$3; domain=$4; out=$5
rm -rf "$out"; mkdir -p "$out"
fail() { echo "FAIL: $*"; exit 1; }
graph="$configs/race_ros2.json"
"$by" validate "$graph" --set bridge.odom_type=nav_msgs::msg::Path > "$out/bad.log" 2>&1; rc=$?
[ $rc = 2 ] && grep -q "odom_type" "$out/bad.log" || { cat "$out/bad.log"; fail "odom_type changed: exit $rc"; }
python3 -c "import json,sys; json.dump({'include': [sys.argv[1]], 'nodes': {'bridge': {'plugin': 'ros2.bridge'}},
  'wires': [{'from': 'gnss_left.fix', 'to': 'bridge.gnss0'}]}, open(sys.argv[2], 'w'))" "$configs/race.json" "$out/no_datum.json" || exit 1
"$by" run "$out/no_datum.json" --domain "$domain" --duration 1 --quiet --progress 0 --no-report > "$out/no_datum.log" 2>&1; rc=$?
[ $rc = 2 ] && grep -q "bridge.*parameters 'datum_latitude' and 'datum_longitude': a gnss input is wired" "$out/no_datum.log" \
  || { cat "$out/no_datum.log"; fail "a gnss input without a datum: exit $rc"; }
for profile in brickyard ros2; do
  "$by" run "$graph" --domain "$domain" --duration 3 --seed 5 --quiet --progress 0 --no-report \
    --arg 'pylons=[{"s": 120, "d": 4.0}, {"s": 150, "d": -4.0}]' \
    --record "$out/$profile.mcap" --record-profile "$profile" --record-scene off > "$out/$profile.log" 2>&1
  [ -s "$out/$profile.mcap" ] || { tail -5 "$out/$profile.log"; fail "recording in the $profile profile"; }
done
node "$clients/mcap_dump.cjs" "$out/brickyard.mcap" gnss_left.fix gnss_right.fix > "$out/fixes.jsonl" || fail "reading the fixes"
python3 "$(dirname "$0")/enu_to_geodetic.py" 39.7930 -86.2389 220.0 "$out/fixes.jsonl" "$out/fixes_ll.json" || fail "latitude and longitude"
node "$clients/ros2_bridge_check.cjs" "$out/ros2.mcap" "$out/fixes_ll.json" > "$out/bridge.json" || fail "the bridge's messages are not what they were made from"
python3 -c "import json,sys; c=json.load(open(sys.argv[1])); e=c.pop('fix_error_m'); print('bridge, read with ROS 2 Humble\'s definitions: ' + ', '.join(f'{v} {k}' for k, v in c.items()) + f', each equal to its source (fixes within {e:.1e} m)')" "$out/bridge.json"
node "$clients/ros2_bag_check.cjs" "$out/ros2.mcap" "$out/brickyard.mcap" > "$out/profiles.json" || fail "the two profiles differ"
python3 -c "import json,sys; t=json.load(open(sys.argv[1]))['topics']; b=[k for k in t if k.startswith('/brickyard/bridge/')]; print(f'{sum(t.values())} messages of {len(t)} topics ({len(b)} of the bridge) equal in both profiles')" "$out/profiles.json"
"$by" bag info "$out/brickyard.mcap" > "$out/info.txt" 2>&1 || { cat "$out/info.txt"; fail "bag info"; }
grep -q "^bridge.odom .*nav_msgs::msg::Odometry" "$out/info.txt" && grep -q "^bridge.points .*sensor_msgs::msg::PointCloud2" "$out/info.txt" \
  || { cat "$out/info.txt"; fail "bag info does not name the bridge's types"; }
"$by" bag play "$out/brickyard.mcap" --domain "$domain" --only bridge.odom > "$out/play.log" 2>&1 &
play=$!
sleep 0.5
"$by" topic echo bridge.odom --domain "$domain" --count 2 --duration 4 > "$out/play_echo.txt" 2>&1; echo_rc=$?
wait $play; play_rc=$?
[ $play_rc = 0 ] && [ $echo_rc = 0 ] && [ "$(grep -c '"child_frame_id"' "$out/play_echo.txt")" = 2 ] \
  || { cat "$out/play.log" "$out/play_echo.txt"; fail "bag play of the bridge's odometry: exit $play_rc, topic echo $echo_rc"; }
echo "bag play: the recorded odometry back on the wire, read by topic echo"

# Live: the bridge's odometry read off the wire by another process, under ROS 2's names.
python3 -c "import json,sys; g={'include': [sys.argv[1]], 'clock': {'mode': 'real'}}; json.dump(g, open(sys.argv[2],'w'))" "$graph" "$out/live.json" || exit 1
"$by" run "$out/live.json" --domain "$domain" --duration 10 --quiet --progress 0 --no-report > "$out/live.log" 2>&1 &
run=$!
sleep 2
"$by" topic echo bridge.odom --naming ros2 --domain "$domain" --count 3 --duration 6 > "$out/echo.txt" 2>&1; echo_rc=$?
wait $run
[ $echo_rc = 0 ] && [ "$(grep -c '"child_frame_id"' "$out/echo.txt")" = 3 ] || { cat "$out/echo.txt"; tail -5 "$out/live.log"; fail "topic echo of bridge.odom: exit $echo_rc"; }
grep -q '"frame_id": *"map"' "$out/echo.txt" || { cat "$out/echo.txt"; fail "the odometry read live is not in the map frame"; }
echo "live: topic echo read 3 nav_msgs/Odometry samples of rt/brickyard/bridge/odom"
echo "ros2_bridge: ok"
