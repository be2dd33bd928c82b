#!/usr/bin/env bash
# `brickyard capture play` (docs/drivers.md, "Captures: info and play"), run in a private network
# namespace (scripts/netns-run: loopback only): an Ouster capture played to drivers.ouster_lidar
# listening on UDP comes out as its three rotations, and its IMU packets to drivers.ouster_imu as
# its 30 samples; a receiver gets the pcap's datagrams to the
# lidar port byte for byte, and a GNSS log's bytes whole, at the recorded pace times --rate; a
# driver polling once a second, woken by its socket, publishes each fix as it arrives; a --loop
# play ends cleanly on SIGINT and on SIGTERM.
set -u
by=$1; data=$2; graphs=$3; domain=$4; out=$5
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$out"; mkdir -p "$out"
fail() { echo "FAIL: $*"; exit 1; }
lidar=$data/lidar_packets/OS-1-128_v2.3.0_1024x10_lb_n3.pcap
python3 "$here/capture_logs.py" "$out" || fail "making the GNSS logs"

# receive NAME: udp_receive.py in the background ($receiver), listening on $port.
receive() {
  python3 "$here/udp_receive.py" "$out/$1.port" "$out/$1" &
  receiver=$!
  for _ in $(seq 200); do [ -s "$out/$1.port" ] && break; sleep 0.05; done
  port=$(cat "$out/$1.port" 2> /dev/null) || fail "the receiver did not start"
}
free_port() { python3 -c 'import socket; s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'; }

# play_to_driver NAME GRAPH NODE PORT: GRAPH run in the background, its NODE listening on a free
# UDP port, the capture's datagrams to PORT played to it; the run must end well ($out/NAME.log).
play_to_driver() {
  local name=$1 graph=$2 node=$3 to=$4 port run
  port=$(free_port)
  "$by" run "$graphs/$graph" --set "$node.source=udp://127.0.0.1:$port" --domain "$domain" > "$out/$name.log" 2>&1 &
  run=$!
  for _ in $(seq 300); do grep -q "\[brickyard\] running" "$out/$name.log" && break; sleep 0.05; done
  "$by" capture play "$lidar" --to udp://127.0.0.1:$port --port "$to" 2> "$out/play_$name.log" || { cat "$out/play_$name.log"; fail "capture play to $node"; }
  wait $run || { cat "$out/$name.log"; fail "$graph did not end well"; }
}

# 1. End to end: the driver, listening, assembles the played packets into the three rotations;
# the same capture's IMU packets (to 7503) reach drivers.ouster_imu as its 30 samples.
play_to_driver ouster ouster_over_udp.json lidar 7502
grep -q "frames_complete 3 .*packets 192" "$out/ouster.log" || { cat "$out/ouster.log"; fail "the driver's counts"; }
cat "$out/play_ouster.log"
play_to_driver ouster_imu ouster_imu_over_udp.json imu 7503
grep -q "malformed 0 · packets 30 · samples 30" "$out/ouster_imu.log" || { cat "$out/ouster_imu.log"; fail "the IMU driver's counts"; }

# 2. The datagrams to 7502 (not the IMU's to 7503), each as captured, at twice the recorded pace.
receive pcap
"$by" capture play "$lidar" --to udp://127.0.0.1:$port --port 7502 --rate 2 2> "$out/play_pcap.log" || { cat "$out/play_pcap.log"; fail "capture play (pcap)"; }
wait $receiver
python3 "$here/capture_check.py" pcap "$lidar" "$out/pcap" "$out/play_pcap.log" 2 || fail "the played pcap"

# 3. GNSS logs: every byte, each log at its time (OEM7 at 20 Hz; NMEA across midnight, 10 x faster).
receive oem7
"$by" capture play "$out/oem7_20hz.GPS" --to udp://127.0.0.1:$port 2> "$out/play_oem7.log" || { cat "$out/play_oem7.log"; fail "capture play (OEM7)"; }
wait $receiver
python3 "$here/capture_check.py" log "$out/oem7_20hz.GPS" "$out/oem7" "$out/play_oem7.log" 1 0.95 21 || fail "the played OEM7 log"
receive nmea
"$by" capture play "$out/nmea_midnight.txt" --to udp://127.0.0.1:$port --rate 10 2> "$out/play_nmea.log" || { cat "$out/play_nmea.log"; fail "capture play (NMEA)"; }
wait $receiver
python3 "$here/capture_check.py" log "$out/nmea_midnight.txt" "$out/nmea" "$out/play_nmea.log" 10 9.0 11 || fail "the played NMEA log"

# 4. A driver woken by its device: drivers.gnss polls once a second, yet publishes each of the 20
# fixes (50 ms apart) within milliseconds of its datagram's arrival (polled alone, up to a second).
port=$(free_port)
"$by" run "$graphs/gnss_woken.json" --set gnss.source=udp://127.0.0.1:$port --domain "$domain" --out "$out/woken" > "$out/woken.log" 2>&1 &
run=$!
for _ in $(seq 300); do grep -q "\[brickyard\] running" "$out/woken.log" && break; sleep 0.05; done
"$by" capture play "$out/oem7_20hz.GPS" --to udp://127.0.0.1:$port 2> "$out/play_woken.log" || { cat "$out/play_woken.log"; fail "capture play to the woken driver"; }
wait $run || { cat "$out/woken.log"; fail "drivers.gnss did not publish the 20 fixes"; }
python3 - "$out/woken/summary.json" <<'PY' || { cat "$out/woken.log"; fail "the woken driver's latency"; }
import json, sys
m = json.load(open(sys.argv[1]))["nodes"]["gnss"]["metrics"]
print(f"woken driver: {m['fixes']:.0f} fixes, wire to message p50 {m['wire_to_message_s_p50']*1e3:.2f} ms, "
      f"p99 {m['wire_to_message_s_p99']*1e3:.2f} ms, max {m['wire_to_message_s_max']*1e3:.2f} ms")
# Polled once a second, 20 fixes 50 ms apart would wait 0.5 s at the median.
sys.exit(0 if m["fixes"] == 20 and m["wire_to_message_s_p50"] < 0.1 else 1)
PY

# 5. --loop plays until a signal, then stops within a moment (its waits are 50 ms slices), exit 0,
# saying so.
for sig in INT TERM; do
  "$by" capture play "$out/oem7_20hz.GPS" --to udp://127.0.0.1:$(free_port) --loop 2> "$out/loop_$sig.log" &
  player=$!
  # The signal once the player says it is sending (before, it is not yet its own to take).
  for _ in $(seq 300); do grep -q "capture play: sending" "$out/loop_$sig.log" && break; sleep 0.05; done
  sleep 2.5
  kill -$sig $player
  t0=$(date +%s.%N)
  wait $player; rc=$?
  took=$(python3 -c "print(f'{$(date +%s.%N) - $t0:.3f}')")
  cat "$out/loop_$sig.log"
  [ $rc -eq 0 ] || fail "SIG$sig: exit $rc"
  grep -q "capture play: [0-9]* messages .*, [1-9][0-9]* whole pass.* (interrupted)" "$out/loop_$sig.log" || fail "SIG$sig: the summary"
  python3 -c "import sys; sys.exit(0 if $took < 1.0 else 1)" || fail "SIG$sig: took $took s to stop"
done
echo "capture_play: ok"
