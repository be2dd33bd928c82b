#!/usr/bin/env bash
# Recordings in ROS 2's form (issue 45, docs/recording.md): the main job, 3 s on the sim clock,
# recorded twice with the same seed, in our profile and in MCAP's ros2 profile; a third party's
# libraries (tests/clients/ros2_bag_check.cjs: @mcap/core, @foxglove/rosmsg,
# @foxglove/rosmsg2-serialization) read the second as a ROS 2 bag and find every message of every
# topic equal to the first's (read by Foxglove's IDL decoder). Both hold the scene (/tf, /scene/*)
# in Foxglove's schemas, every message valid by Foxglove's published JSON schemas
# (tests/clients/scene_check.cjs); --record-scene off leaves it out, and so does --record-only
# unless --record-scene on. Our own `bag info` names the
# ros2 recording's topics and types as ours. --record-profile ros1, --record-scene maybe, or ros2
# into a .db3: exit 2, named.
# usage: ros2_recording.sh BRICKYARD CLIENTS RACE_GRAPH DOMAIN OUT
set -u
by=$1; clients=$2; race=$3; domain=$4; out=$5
rm -rf "$out"; mkdir -p "$out"
fail() { echo "FAIL: $*"; exit 1; }
"$by" run "$race" --record-profile ros1 --record "$out/x.mcap" > "$out/bad.log" 2>&1; rc=$?
[ $rc = 2 ] && grep -q "\-\-record-profile ros1: expected brickyard or ros2" "$out/bad.log" || { cat "$out/bad.log"; fail "--record-profile ros1: exit $rc"; }
"$by" run "$race" --record-profile ros2 --record "$out/x.db3" > "$out/bad_db3.log" 2>&1; rc=$?
[ $rc = 2 ] && grep -q "x.db3 is SQLite (name a .mcap file)" "$out/bad_db3.log" || { cat "$out/bad_db3.log"; fail "--record-profile ros2 into a .db3: exit $rc"; }
"$by" run "$race" --record-scene maybe --record "$out/x.mcap" > "$out/bad_scene.log" 2>&1; rc=$?
[ $rc = 2 ] && grep -q "\-\-record-scene maybe: expected on or off" "$out/bad_scene.log" || { cat "$out/bad_scene.log"; fail "--record-scene maybe: exit $rc"; }
[ ! -e "$out/x.db3" ] && [ ! -e "$out/x.mcap" ] || fail "a refused run left a file"
for profile in brickyard ros2; do
  "$by" run "$race" --domain "$domain" --duration 3 --seed 5 --quiet --progress 0 --no-report \
    --record "$out/$profile.mcap" --record-profile "$profile" > "$out/$profile.log" 2>&1
  [ -s "$out/$profile.mcap" ] || { tail -5 "$out/$profile.log"; fail "recording in the $profile profile"; }
  node "$clients/scene_check.cjs" "$out/$profile.mcap" > "$out/scene_$profile.json" || fail "the $profile recording's scene"
  echo "$profile profile, the scene: $(cat "$out/scene_$profile.json")"
done
"$by" run "$race" --domain "$domain" --duration 1 --seed 5 --quiet --progress 0 --no-report --record "$out/no_scene.mcap" --record-scene off \
  > "$out/no_scene.log" 2>&1
for how in "" "--record-scene on"; do  # --record-only: the wires it names, the scene only when said
  f=only${how:+_scene}
  "$by" run "$race" --domain "$domain" --duration 1 --seed 5 --quiet --progress 0 --no-report --record "$out/$f.mcap" \
    --record-only estimator.estimate $how > "$out/$f.log" 2>&1
done
for f in brickyard no_scene only only_scene; do "$by" bag info "$out/$f.mcap" > "$out/info_$f.txt" 2>&1 || { cat "$out/info_$f.txt"; fail "bag info $f.mcap"; }; done
grep -q "^/tf .*foxglove.FrameTransform" "$out/info_brickyard.txt" || { cat "$out/info_brickyard.txt"; fail "bag info does not list /tf"; }
grep -q "^estimator.estimate " "$out/info_no_scene.txt" && ! grep -q "^/tf " "$out/info_no_scene.txt" \
  || { cat "$out/info_no_scene.txt"; fail "--record-scene off: /tf recorded, or the wires not"; }
grep -q "^estimator.estimate " "$out/info_only.txt" && ! grep -q "^/tf " "$out/info_only.txt" || { cat "$out/info_only.txt"; fail "--record-only recorded the scene"; }
grep -q "^/tf " "$out/info_only_scene.txt" || { cat "$out/info_only_scene.txt"; fail "--record-only with --record-scene on: no /tf"; }
node "$clients/ros2_bag_check.cjs" "$out/ros2.mcap" "$out/brickyard.mcap" > "$out/check.json" || fail "the ros2 recording is not the same run read as a ROS 2 bag"
python3 -c "import json,sys; t=json.load(open(sys.argv[1]))['topics']; print(f'{sum(t.values())} messages of {len(t)} topics read as a ROS 2 bag, each equal to our profile\'s')" "$out/check.json"
"$by" bag info "$out/ros2.mcap" > "$out/info.txt" 2>&1 || { cat "$out/info.txt"; fail "bag info of the ros2 recording"; }
grep -q "estimator.estimate .*brickyard::msgs::LocalizationEstimate" "$out/info.txt" || { cat "$out/info.txt"; fail "bag info does not name the ros2 recording's topics as ours"; }
echo "ros2_recording: ok"
