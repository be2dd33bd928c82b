#!/usr/bin/env bash
# Issue 43, "Recording": the bus in the recording and back out of it. race_can_ims.json runs 3 s,
# its vehicle interface's frames output recorded (uncompressed, so its decoded signals' names can
# be read in the file); brickyard-can writes the frames as a candump log: one line per frame the
# interface wrote or read (its metrics' frames_sent + bus_frames_in), can-utils' format; then plays
# the log as cannelloni datagrams to a UDP socket, and the frames that arrive are the log's, in order.
# usage: can_recording.sh BY BY_CAN GRAPHS DOMAIN OUT
set -u
by=$1; by_can=$2; graphs=$3; domain=$4; out=$5
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$out"; mkdir -p "$out"
"$by" run "$graphs/race_can_ims.json" --threads 1 --domain "$domain" --quiet --progress 0 --duration 3 --out "$out/run" --no-report \
  --record "$out/bus.mcap" --record-only 'vehicle.frames' --record-compression none > "$out/run.log" 2>&1
[ -s "$out/run/summary.json" ] || { cat "$out/run.log"; echo "FAIL: the run wrote no summary"; exit 1; }
for name in steering_motor_ang_cmd wheel_speed_report brake_pressure_cmd; do
  grep -q -a "$name" "$out/bus.mcap" || { echo "FAIL: no '$name' in the recording: the frames are not decoded"; exit 1; }
done
"$by_can" candump "$out/bus.mcap" --out "$out/bus.log" || { echo "FAIL: brickyard-can candump"; exit 1; }
python3 - "$out/run/summary.json" "$out/bus.log" <<'PY' || exit 1
import json, re, sys
m = json.load(open(sys.argv[1]))["nodes"]["vehicle"]["metrics"]
lines = open(sys.argv[2]).read().splitlines()
want = m["frames_sent"] + m["bus_frames_in"]
ok = all(re.fullmatch(r"\(\d{10}\.\d{6}\) can0 [0-9A-F]{3}#[0-9A-F]*", l) for l in lines)
ids = {int(l.split()[2].split("#")[0], 16) for l in lines}
print(f"candump log: {len(lines)} frames (the interface wrote {m['frames_sent']:.0f} and read {m['bus_frames_in']:.0f}); ids {sorted(ids)}")
sys.exit(0 if ok and len(lines) == want and {1300, 1400, 1402, 1404} <= ids else 1)
PY
python3 "$here/udp_receive.py" "$out/port" "$out/received" &
receiver=$!
for _ in $(seq 50); do [ -s "$out/port" ] && break; sleep 0.1; done
"$by_can" play "$out/bus.log" --to "udp://127.0.0.1:$(cat "$out/port")" --rate 0 || { kill $receiver; echo "FAIL: brickyard-can play"; exit 1; }
wait $receiver
python3 - "$out/bus.log" "$out/received.bin" "$out/received.json" <<'PY' || exit 1
import json, struct, sys
log = [l.split()[2] for l in open(sys.argv[1]).read().splitlines()]
data, sizes = open(sys.argv[2], "rb").read(), json.load(open(sys.argv[3]))["sizes"]
frames, at = [], 0
for size in sizes:  # cannelloni v2: version, op, sequence, count (16 bits), then id (32), length, data
    d = data[at:at + size]; at += size
    assert d[0] == 2 and d[1] == 0, "not a cannelloni v2 DATA datagram"
    n, p = struct.unpack(">H", d[3:5])[0], 5
    for _ in range(n):
        can_id, length = struct.unpack(">IB", d[p:p + 5]); p += 5
        frames.append(f"{can_id & 0x7FF:03X}#{d[p:p + length].hex().upper()}"); p += length
print(f"played: {len(frames)} frames in {len(sizes)} datagrams; the same as the log's: {frames == log}")
sys.exit(0 if frames == log else 1)
PY
echo "can_recording: ok"
