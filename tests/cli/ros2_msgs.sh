#!/usr/bin/env bash
# The ROS 2 message package (issue 45, docs/ros2.md): `brickyard ros2 msgs` writes the one kept in
# sdk/ros2/brickyard_msgs (kept in step with sdk/msgs: regenerate it when a message changes);
# written again into its own folder it removes a message the SDK no longer has; a folder that is
# not the package's, or no --out, is refused (exit 2, named). With a recording (the main job,
# 2 s, every type it publishes), a third party's ROS 2 libraries read every sample by the
# package's definitions exactly as the IDL reads it (tests/clients/ros2_msgs_check.cjs).
# usage: ros2_msgs.sh BRICKYARD SOURCE_DIR DOMAIN OUT [RACE_GRAPH]
set -u
by=$1; src=$2; domain=$3; out=$4; race=${5:-}
rm -rf "$out"; mkdir -p "$out"
fail() { echo "FAIL: $*"; exit 1; }
"$by" ros2 msgs --out "$out/brickyard_msgs" || fail "ros2 msgs"
diff -r "$src/sdk/ros2/brickyard_msgs" "$out/brickyard_msgs" \
  || fail "sdk/ros2/brickyard_msgs is not what ros2 msgs writes: run \`brickyard ros2 msgs --out sdk/ros2/brickyard_msgs\`"
echo "# gone" > "$out/brickyard_msgs/msg/Gone.msg"
"$by" ros2 msgs --out "$out/brickyard_msgs" > /dev/null || fail "ros2 msgs into its own package"
[ ! -e "$out/brickyard_msgs/msg/Gone.msg" ] || fail "a message the SDK has not was left in msg/"
mkdir -p "$out/other" && echo x > "$out/other/notes.txt"
"$by" ros2 msgs --out "$out/other" > "$out/other.log" 2>&1; rc=$?
[ $rc = 2 ] && grep -q "other: holds files and no brickyard_msgs package" "$out/other.log" || { cat "$out/other.log"; fail "exit $rc into a foreign folder"; }
[ "$(ls "$out/other")" = notes.txt ] || fail "files written into a foreign folder"
: > "$out/a_file"
"$by" ros2 msgs --out "$out/a_file" > "$out/file.log" 2>&1; rc=$?
[ $rc = 2 ] && grep -q "a_file: not a folder" "$out/file.log" || { cat "$out/file.log"; fail "exit $rc with --out a file"; }
"$by" ros2 msgs > "$out/none.log" 2>&1; rc=$?
[ $rc = 2 ] && grep -q "needs --out DIR" "$out/none.log" || { cat "$out/none.log"; fail "exit $rc without --out"; }
# The same messages in IDL on ROS 2's DDS names (tests/cli/ros2_cyclone.sh compiles a Cyclone DDS peer from it).
"$by" ros2 idl --out "$out/dds.idl" > /dev/null || fail "ros2 idl"
grep -q "^@final struct LocalizationEstimate_ {" "$out/dds.idl" && grep -q "^module dds_ {" "$out/dds.idl" || fail "ros2 idl: no dds_ module or type"
"$by" ros2 idl --out "$out/other" > "$out/idl_dir.log" 2>&1; rc=$?
[ $rc = 2 ] && grep -q "other: a folder: name the IDL file to write" "$out/idl_dir.log" || { cat "$out/idl_dir.log"; fail "ros2 idl --out a folder: exit $rc"; }
"$by" ros2 idl > "$out/idl_none.log" 2>&1; rc=$?
[ $rc = 2 ] && grep -q "needs --out FILE" "$out/idl_none.log" || { cat "$out/idl_none.log"; fail "ros2 idl without --out: exit $rc"; }
if [ -n "$race" ]; then
  "$by" run "$race" --domain "$domain" --duration 2 --quiet --progress 0 --no-report --record "$out/race.mcap" > "$out/race.log" 2>&1
  [ -s "$out/race.mcap" ] || { cat "$out/race.log"; fail "recording the race"; }
  node "$src/tests/clients/ros2_msgs_check.cjs" "$out/brickyard_msgs" "$out/race.mcap" > "$out/check.json" || fail "the ROS 2 definitions do not read the recording as its IDL does"
  python3 -c "import json,sys; c=json.load(open(sys.argv[1])); t=c['topics']; print(f\"{sum(v['count'] for v in t.values())} messages of {len(t)} topics, {len(set(v['type'] for v in t.values()))} types, read alike by the package's ROS 2 definitions and the IDL\")" "$out/check.json"
fi
echo "ros2_msgs: ok"
