#!/usr/bin/env bash
# ROS 2's names on the wire (issue 45, docs/ros2.md): tests/graphs/multiprocess/two_process.json
# with "transport": {"naming": "ros2"}, supervised on the real clock and secured by default (its
# permissions name the topics as the wire does): b's sink gets a's samples; meanwhile, as a ROS 2
# tool would see them, `topic list` hears the writer of src.out on "rt/brickyard/src/out" with
# the type "brickyard_msgs::msg::dds_::Scalar_" (the package `brickyard ros2 msgs` writes),
# `topic echo --naming ros2` reads its samples, and without --naming no writer of that name is
# found. A value of naming other than the two: exit 2, named.
# usage: ros2_naming.sh BRICKYARD GRAPH DOMAIN OUT
set -u
by=$1; graph=$2; domain=$3; out=$4
rm -rf "$out"; mkdir -p "$out"
fail() { echo "FAIL: $*"; exit 1; }
python3 -c "import json,sys; g=json.load(open(sys.argv[1])); g['transport']={'naming': sys.argv[3]}; json.dump(g, open(sys.argv[2],'w'))" \
  "$graph" "$out/ros2.json" ros2 || exit 1
python3 -c "import json,sys; g=json.load(open(sys.argv[1])); g['transport']={'naming': sys.argv[3]}; json.dump(g, open(sys.argv[2],'w'))" \
  "$graph" "$out/bad.json" ros1 || exit 1
"$by" validate "$out/bad.json" > "$out/bad.log" 2>&1; rc=$?
[ $rc = 2 ] && grep -q 'bad.json#/transport/naming: expected "brickyard" or "ros2", found "ros1"' "$out/bad.log" || { cat "$out/bad.log"; fail "naming ros1: exit $rc"; }
"$by" topic echo src.out --naming ros1 --domain "$domain" > "$out/bad_flag.log" 2>&1; rc=$?
[ $rc = 2 ] && grep -q "\-\-naming ros1: expected brickyard or ros2" "$out/bad_flag.log" || { cat "$out/bad_flag.log"; fail "--naming ros1: exit $rc"; }

"$by" run "$out/ros2.json" --domain "$domain" --duration 12 --progress 0 --no-report --out "$out/run" 2> "$out/run.log" &
sup=$!
for _ in $(seq 1 100); do grep -q "\[b\] .*running" "$out/run.log" && break; sleep 0.1; done
keys=$(sed -n 's/.*for the graph in \(.*\) ("off" turns this off.*/\1/p' "$out/run.log" | head -n 1)
[ -n "$keys" ] || { cat "$out/run.log"; kill $sup; fail "the run did not say where its keys are"; }
"$by" topic list --domain "$domain" --security "$keys" > "$out/list.txt" 2>&1
"$by" topic echo src.out --naming ros2 --domain "$domain" --security "$keys" --count 3 > "$out/echo.txt" 2>&1; echo_rc=$?
"$by" topic echo src.out --domain "$domain" --security "$keys" --count 3 --duration 3 > "$out/echo_ours.txt" 2>&1; ours_rc=$?
wait $sup; rc=$?
[ $rc = 0 ] || { tail -5 "$out/run.log"; fail "the run: exit $rc"; }
cat "$out/list.txt"
grep -q "^src.out .*brickyard::msgs::Scalar  (ROS 2 names: rt/brickyard/src/out, brickyard_msgs::msg::dds_::Scalar_)" "$out/list.txt" \
  || fail "topic list did not hear src.out under ROS 2's names"
[ $echo_rc = 0 ] && [ "$(grep -c '"value"' "$out/echo.txt")" = 3 ] || { cat "$out/echo.txt"; fail "topic echo --naming ros2: exit $echo_rc"; }
[ $ours_rc = 1 ] || { cat "$out/echo_ours.txt"; fail "topic echo without --naming: exit $ours_rc, expected 1 (no writer of brickyard/src/out)"; }
echo "ros2_naming: ok"
