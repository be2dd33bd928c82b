#!/usr/bin/env bash
# Point clouds recorded compact (--record-cloud-precision, docs/recording.md): the same run's three
# LiDARs recorded exact and to 1 cm; the compact MCAP file read by Foxglove's own reader, every
# message decoded by its OMG IDL; at most a third of the exact file's size; replayed by
# replay.point_cloud as PointClouds whose every coordinate lies within half a centimetre of the
# exact recording's, with the same stamps and mounts; bag play republishes them as PointClouds.
# Bad values and damaged compact samples: exit 2.
set -u
by=$1; graphs=$2; domain=$3; out=$4; clients=$5
rm -rf "$out"; mkdir -p "$out"
run="$graphs/sim_all_sensors.json"
only='lidar_*.cloud'
"$by" run "$run" --domain "$domain" --quiet --record "$out/exact.mcap" --record-only "$only" || { echo "FAIL: exact recording"; exit 1; }
"$by" run "$run" --domain "$domain" --quiet --record "$out/cm.mcap" --record-only "$only" --record-cloud-precision 0.01 \
  || { echo "FAIL: compact recording"; exit 1; }
"$by" run "$run" --domain "$domain" --quiet --record "$out/exact.db3" --record-only "$only" || { echo "FAIL: exact recording (.db3)"; exit 1; }
"$by" run "$run" --domain "$domain" --quiet --record "$out/cm.db3" --record-only "$only" --record-cloud-precision 0.01 \
  || { echo "FAIL: compact recording (.db3)"; exit 1; }
node "$clients/mcap_check.cjs" "$out/cm.mcap" > "$out/cm.json" || { echo "FAIL: @mcap/core or the decoder refused cm.mcap"; exit 1; }
replay="$graphs/replay/cloud_from_recording.json"
"$by" run "$replay" --domain "$domain" --quiet --set lidar_front.file="$out/cm.db3" --record "$out/replayed.db3" \
  --record-only 'lidar_front.out' || { echo "FAIL: replay of the compact recording"; exit 1; }
"$by" run "$replay" --domain "$domain" --quiet --set lidar_front.file="$out/cm.mcap" > "$out/replay_mcap.log" 2>&1 \
  || { cat "$out/replay_mcap.log"; echo "FAIL: replay of the compact MCAP recording"; exit 1; }
python3 - "$out" <<'PY' || exit 1
import json, os, sqlite3, struct, sys
out = sys.argv[1]
got = json.load(open(f"{out}/cm.json"))
schemas = {t: v["schema"] for t, v in got["topics"].items()}
exact, cm = os.path.getsize(f"{out}/exact.mcap"), os.path.getsize(f"{out}/cm.mcap")
print(f"compact: {got['messages']} messages decoded by @mcap/core, schemas {sorted(set(schemas.values()))}; "
      f"{cm / 1e6:.1f} MB against {exact / 1e6:.1f} MB exact ({exact / cm:.2f}x)")
def cloud(b):
    o = 4
    stamp = struct.unpack_from("<q", b, o)[0]; o += 12
    n = struct.unpack_from("<I", b, o)[0]; o += 4 + n
    sensor_id = b[o]; o += 1
    o = 4 + (((o - 4) + 7) & ~7)
    mount = struct.unpack_from("<6d", b, o); o += 48
    arrs = []
    for _ in range(4):
        o = 4 + (((o - 4) + 3) & ~3)
        n = struct.unpack_from("<I", b, o)[0]; o += 4
        arrs.append(struct.unpack_from(f"<{n}f", b, o)); o += 4 * n
    return stamp, sensor_id, mount, arrs
def rows(f, topic):
    return [cloud(d) for (d,) in sqlite3.connect(f).execute(
        "SELECT m.data FROM messages m JOIN topics t ON t.id = m.topic_id WHERE t.name = ? ORDER BY m.id", (topic,))]
a, b = rows(f"{out}/exact.db3", "lidar_front.cloud"), rows(f"{out}/replayed.db3", "lidar_front.out")
worst, points, same_meta = 0.0, 0, 0
for (sa, ia, ma, xa), (sb, ib, mb, xb) in zip(a, b):
    same_meta += sa == sb and ia == ib and ma == mb and len(xa[0]) == len(xb[0])
    for k in range(3):
        for u, v in zip(xa[k], xb[k]):
            worst = max(worst, abs(u - v)); points += 1
print(f"replayed: {len(b)} clouds of {len(a)}, {same_meta} with the same stamp, sensor, mount and size; "
      f"{points} coordinates within {worst * 1000:.2f} mm of the exact recording's")
ok = len(a) > 50 and len(a) == len(b) == same_meta and worst <= 0.005 + 2e-5
ok = ok and all(s == "brickyard::msgs::QuantizedPointCloud" for s in schemas.values()) and len(schemas) == 3
ok = ok and exact / cm >= 3
sys.exit(0 if ok else 1)
PY
# bag play: the compact clouds republished over DDS as the PointClouds they were, heard by topic echo.
"$by" bag play "$out/cm.mcap" --domain "$domain" --only 'lidar_front.*' > "$out/play.log" 2>&1 &
play=$!
"$by" topic echo lidar_front.cloud --domain "$domain" --count 2 > "$out/echo.jsonl" 2> "$out/echo.err" \
  || { cat "$out/echo.err"; echo "FAIL: topic echo of played compact clouds"; exit 1; }
kill -INT $play 2> /dev/null; wait $play 2> /dev/null
python3 - "$out/echo.jsonl" <<'PY' || exit 1
import json, sys
clouds = [json.loads(l) for l in open(sys.argv[1])]
n = [len(c.get("x", [])) for c in clouds]
print(f"bag play: {len(clouds)} clouds echoed as PointCloud, {n} points, stamps {[c['header']['stamp_ns'] for c in clouds]}")
sys.exit(0 if len(clouds) == 2 and all(k > 1000 for k in n) and all(len(c["intensity"]) == len(c["x"]) for c in clouds) else 1)
PY
expect2() {  # pattern, then the command
  pat=$1; shift
  "$@" > "$out/bad.log" 2>&1; rc=$?
  [ $rc -eq 2 ] || { cat "$out/bad.log"; echo "FAIL: exit $rc, expected 2: $*"; exit 1; }
  grep -q -- "$pat" "$out/bad.log" || { cat "$out/bad.log"; echo "FAIL: message lacks '$pat'"; exit 1; }
}
# A damaged compact sample: cut short (the CDR does not decode), or a precision out of range (it
# decodes, and does not restore): exit 2 naming the recording and the sample.
python3 - "$out/cm.db3" "$out/cut.db3" "$out/precision.db3" <<'PY'
import shutil, sqlite3, struct, sys
for dst, how in ((sys.argv[2], "cut"), (sys.argv[3], "precision")):
    shutil.copy(sys.argv[1], dst)
    c = sqlite3.connect(dst)
    mid, d = c.execute("SELECT m.id, m.data FROM messages m JOIN topics t ON t.id = m.topic_id "
                       "WHERE t.name = 'lidar_front.cloud' ORDER BY m.id LIMIT 1").fetchone()
    d = bytearray(d)
    if how == "cut":
        d = d[:len(d) // 2]
    else:  # precision_m: after the header, sensor_id and the six doubles of the mount
        o = 16 + 4 + struct.unpack_from("<I", d, 16)[0] + 1
        o = 4 + (((o - 4) + 7) & ~7) + 48
        struct.pack_into("<d", d, o, 5.0)
    c.execute("UPDATE messages SET data = ? WHERE id = ?", (bytes(d), mid)); c.commit()
PY
expect2 "cut.db3: sample 0 of 'lidar_front.cloud' does not decode as brickyard::msgs::QuantizedPointCloud: its first" \
  "$by" run "$replay" --domain "$domain" --set lidar_front.file="$out/cut.db3"
expect2 "precision.db3: sample 0 of 'lidar_front.cloud' does not decode as brickyard::msgs::QuantizedPointCloud: precision_m 5.000000: expected (0, 1\] m" \
  "$by" run "$replay" --domain "$domain" --set lidar_front.file="$out/precision.db3"
expect2 "--record-cloud-precision: expected metres, more than 0 and at most 0.1" "$by" run "$run" --record "$out/x.mcap" --record-cloud-precision 0.5
expect2 "--record-cloud-precision: needs --record FILE" "$by" run "$run" --record-cloud-precision 0.01
echo "cloud precision: ok"
