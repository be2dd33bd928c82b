#!/usr/bin/env bash
# The live view (docs/live.md), watched by Foxglove's own client: `brickyard run --live` serves the
# main job; @foxglove/ws-protocol connects, finds every wire advertised with its OMG IDL schema,
# subscribes to all but the clouds and decodes every message; what it got is, topic by topic,
# exactly what the run recorded over the same span. Meanwhile clients that misbehave (garbage,
# unknown channels, a flood, one that never reads, one that leaves mid-frame) are answered or cut
# off, and the run is the same, sample for sample, as one without the server. Bad flags: exit 2.
set -u
by=$1; configs=$2; domain=$3; out=$4; clients=$5
rm -rf "$out"; mkdir -p "$out"
graph="$configs/ims_race.json"
port=8765
"$by" run "$graph" --domain "$domain" --quiet --progress 0 --duration 16 --set referee.laps=0 --pace 4 --live $port --out "$out/live" > "$out/live.log" 2>&1 &
pid=$!
node "$clients/live_check.cjs" "ws://127.0.0.1:$port" "$out/watched.json" --skip brickyard::msgs::PointCloud --skip brickyard::msgs::ClusterList \
  --skip foxglove::PointCloud --keep /lidar/lidar_front.cloud \
  > "$out/watch.log" 2>&1 &
watcher=$!
sleep 1
ss -ltn > "$out/listening.txt" 2>&1
node "$clients/live_abuse.cjs" 127.0.0.1 $port > "$out/abuse.json" 2> "$out/abuse.log"
wait $pid; rc=$?
[ $rc -eq 0 ] || { cat "$out/live.log"; echo "FAIL: the live run exited $rc"; exit 1; }
wait $watcher || { cat "$out/watch.log"; echo "FAIL: Foxglove's client refused the live stream"; exit 1; }
grep -q "127.0.0.1:$port " "$out/listening.txt" && ! grep -q "0.0.0.0:$port \|\*:$port " "$out/listening.txt" \
  || { cat "$out/listening.txt"; echo "FAIL: the server listened beyond loopback"; exit 1; }
node "$clients/mcap_check.cjs" "$out/live/recording.mcap" --window "$out/watched.json" > "$out/recorded.json" \
  || { echo "FAIL: the recording"; exit 1; }
python3 - "$out/watched.json" "$out/recorded.json" "$out/live/summary.json" "$out/abuse.json" <<'PY' || exit 1
import json, sys
watched, recorded, summary, abuse = (json.load(open(f)) for f in sys.argv[1:5])
topics = {t: v for t, v in watched["topics"].items() if not t.startswith("/")}   # the wires
scene = {t: v["count"] for t, v in watched["topics"].items() if t.startswith("/")}  # Foxglove's schemas
same = [t for t, v in topics.items() if v["count"] == recorded["topics"].get(t, {}).get("count") and v["sha256"] == recorded["topics"][t]["sha256"]]
n = sum(v["count"] for v in topics.values())
live = summary["live"]
print(f"watched live: {len(watched['channels'])} channels advertised, {len(topics)} subscribed, {n} messages decoded, "
      f"{len(same)} of {len(topics)} topics identical to the recording over the same span; {watched['time_messages']} time messages, "
      f"the last at {watched['last_time'] / 1e9:.2f} s")
print(f"scene (each message valid against Foxglove's schema): {json.dumps(scene)}")
print(f"server: {live['clients']} clients, {live['sent']} frames sent, {live['dropped']} dropped (the client that never read), "
      f"{live['clouds_thinned']} clouds thinned to {live['cloud_hz']} a second, "
      f"{live['refused_requests']} requests refused, {live['disconnected']} disconnected; abuse: {json.dumps(abuse)}")
ok = len(same) == len(topics) and len(topics) >= 10 and n > 5000
ok = ok and all(scene.get(t, 0) > 0 for t in ["/tf", "/scene/track", "/scene/path", "/scene/wall", "/scene/obstacles", "/lidar/lidar_front.cloud"])
ok = ok and "/lidar/lidar_left.cloud" not in scene
ok = ok and "time" in watched["serverInfo"]["capabilities"] and watched["last_time"] >= 15e9
ok = ok and all(c["schemaEncoding"] == "omgidl" and c["encoding"] == "cdr" for c in watched["channels"] if not c["topic"].startswith("/"))
# Clouds at most 20 a second of wall time (--live-cloud-hz): 16 s of sim at --pace 4 take at
# least 4 s, 80 clouds of the front LiDAR's 320 (a little more for the span of the last interval).
ok = ok and live["cloud_hz"] == 20 and live["clouds_thinned"] > 0 and 0 < scene["/lidar/lidar_front.cloud"] <= 20 * 16 / 4 * 1.2
ok = ok and watched["last"]["/lidar/lidar_front.cloud"]["point_stride"] == 16 and watched["last"]["/lidar/lidar_front.cloud"]["data"]["bytes"] > 100000
ok = ok and abuse["garbage"]["statuses"] >= 3 and abuse["bad_subscriptions"]["statuses"] >= 3
ok = ok and abuse["flood"]["closed"] and live["disconnected"] >= 1 and live["dropped"] > 0 and live["clients"] >= 6
sys.exit(0 if ok else 1)
PY
# The same run without the server: the same samples.
"$by" run "$graph" --domain "$domain" --quiet --progress 0 --duration 16 --set referee.laps=0 --out "$out/plain" > "$out/plain.log" 2>&1 \
  || { cat "$out/plain.log"; echo "FAIL: the run without --live"; exit 1; }
python3 "$(dirname "$0")/same_recordings.py" "$out/live/recording.mcap" "$out/plain/recording.mcap" \
  || { echo "FAIL: serving the run live changed it"; exit 1; }
expect2() {  # pattern, then the command
  pat=$1; shift
  "$@" > "$out/bad.log" 2>&1; rc=$?
  [ $rc -eq 2 ] || { cat "$out/bad.log"; echo "FAIL: exit $rc, expected 2: $*"; exit 1; }
  grep -q -- "$pat" "$out/bad.log" || { cat "$out/bad.log"; echo "FAIL: message lacks '$pat'"; exit 1; }
}
expect2 "--live 70000: expected a port from 0 to 65535" "$by" run "$graph" --live 70000
expect2 "--live nope.example:8765: cannot listen (not an IP address)" "$by" run "$graph" --domain "$domain" --duration 1 --live 8765 --live-address nope.example
expect2 "--pace: expected a factor of real time from 0.001 to 1e6" "$by" run "$graph" --pace 0
expect2 "--pace: expected a factor of real time from 0.001 to 1e6" "$by" run "$graph" --pace 1e-30
expect2 "--live-cloud-hz: expected clouds a second from 0 (every one) to 1000" "$by" run "$graph" --live-cloud-hz -1
expect2 "--pace: the graph runs on the real clock" "$by" run "$configs/../tests/graphs/real_clock.json" --pace 2
python3 -c "import socket,time; s=socket.socket(); s.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1); s.bind(('127.0.0.1', $port)); s.listen(); time.sleep(30)" &
holder=$!
for i in $(seq 50); do ss -ltn | grep -q "127.0.0.1:$port " && break; sleep 0.1; done
expect2 "--live 127.0.0.1:$port: cannot listen" "$by" run "$graph" --domain "$domain" --duration 1 --live $port
kill $holder 2> /dev/null
echo "live_view: ok"
