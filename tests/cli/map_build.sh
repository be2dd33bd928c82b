#!/usr/bin/env bash
# brickyard map build (issue 17): a recording of the mapping drive (its LiDARs' clouds, the
# fusion's estimates and the IMU) built into a map by configs/map_build.json gives the map the drive itself
# wrote, byte for byte, and so does the same drive recorded on the real clock (re-timed); a drive that never closed a lap gives no track file (exit 2, the reason);
# and each way a recording can be unfit is refused with exit 2 naming the file and what is wrong.
set -u
by=$1; configs=$2; graphs=$3; domain=$4; out=$5
rm -rf "$out"; mkdir -p "$out"
rec="$out/drive.db3"
"$by" run "$configs/map_ims.json" --domain "$domain" --quiet --progress 0 --duration 4 --arg map_file="$out/live.pcd" \
  --record "$rec" --record-only 'lidar_*.cloud,estimator.estimate,imu.imu' > "$out/drive.log" 2>&1
[ -s "$out/live.pcd" ] || { cat "$out/drive.log"; echo "FAIL: the drive wrote no map"; exit 1; }
expect2() {  # pattern, then the command
  pat=$1; shift
  "$@" > "$out/bad.log" 2>&1; rc=$?
  [ $rc -eq 2 ] || { cat "$out/bad.log"; echo "FAIL: exit $rc, expected 2: $*"; exit 1; }
  grep -q -- "$pat" "$out/bad.log" || { cat "$out/bad.log"; echo "FAIL: message lacks '$pat'"; exit 1; }
}
mkdir -p "$out/built"; touch "$out/built/track.csv"  # an earlier build's, which must not stand for this one's
expect2 "drive.db3: no track from this drive: .*the drive never came back to where it started" \
  "$by" map build "$rec" --out "$out/built" --domain "$domain" --progress 0
cmp "$out/live.pcd" "$out/built/map.pcd" || { echo "FAIL: the map built from the recording differs from the drive's"; exit 1; }
[ ! -e "$out/built/track.csv" ] || { echo "FAIL: a track file stands after a build that made none"; exit 1; }
[ ! -e "$out/built/track.csv.part" ] || { echo "FAIL: a half-written track file was left"; exit 1; }
grep -q '"registered"' "$out/built/summary.json" || { echo "FAIL: no summary"; exit 1; }
echo "the map built from the recording is the drive's, byte for byte ($(stat -c %s "$out/live.pcd") bytes)"

expect2 "nope.db3: no such file" "$by" map build "$out/nope.db3" --out "$out/x"
echo "not a database" > "$out/text.db3"
expect2 "text.db3: not a readable recording: file is not a database" "$by" map build "$out/text.db3" --out "$out/x"
head -c 100000 "$rec" > "$out/truncated.db3"
expect2 "truncated.db3: not a readable recording" "$by" map build "$out/truncated.db3" --out "$out/x"
"$by" run "$configs/map_ims.json" --domain "$domain" --quiet --progress 0 --duration 0.5 --record "$out/empty.db3" --record-only 'no.such' > /dev/null 2>&1
expect2 "empty.db3: the recording holds no samples" "$by" map build "$out/empty.db3" --out "$out/x"
"$by" run "$configs/map_ims.json" --domain "$domain" --quiet --progress 0 --duration 0.5 --record "$out/estimates.db3" --record-only 'estimator.estimate' > /dev/null 2>&1
expect2 "recording .*estimates.db3 has no topic 'imu.imu' (it has: estimator.estimate)" \
  "$by" map build "$out/estimates.db3" --out "$out/x" --domain "$domain"
"$by" run "$configs/map_ims.json" --domain "$domain" --quiet --progress 0 --duration 0.5 --record "$out/clouds.db3" --record-only 'lidar_*.cloud' > /dev/null 2>&1
expect2 "recording .*clouds.db3 has no topic 'estimator.estimate' (it has: lidar_front.cloud" \
  "$by" map build "$out/clouds.db3" --out "$out/x" --domain "$domain"
"$by" run "$configs/map_ims.json" --domain "$domain" --quiet --progress 0 --duration 0.5 --record "$out/no_imu.db3" --record-only 'lidar_*.cloud,estimator.estimate' > /dev/null 2>&1
expect2 "recording .*no_imu.db3 has no topic 'imu.imu'" "$by" map build "$out/no_imu.db3" --out "$out/x" --domain "$domain"
# A real drive's recording (Unix times, clock "real"): the same drive with every time and header
# stamp moved to 2026 builds the same map, re-timed from its first sample.
python3 - "$rec" "$out/drive_real.db3" <<'PY'
import shutil, sqlite3, struct, sys
shutil.copy(sys.argv[1], sys.argv[2])
c = sqlite3.connect(sys.argv[2])
epoch = 1796000000 * 10**9
rows = c.execute("SELECT id, timestamp, data FROM messages").fetchall()
for i, t, d in rows:
    d = bytearray(d)
    struct.pack_into("<q", d, 4, struct.unpack_from("<q", d, 4)[0] + epoch)  # the header's stamp_ns
    c.execute("UPDATE messages SET timestamp = ?, data = ? WHERE id = ?", (t + epoch, bytes(d), i))
c.execute("UPDATE metadata SET value = 'real' WHERE key = 'clock'")
c.commit()
PY
mkdir -p "$out/built_real"
expect2 "drive_real.db3: no track from this drive: .*the drive never came back to where it started" \
  "$by" map build "$out/drive_real.db3" --out "$out/built_real" --domain "$domain" --progress 0
cmp "$out/live.pcd" "$out/built_real/map.pcd" || { echo "FAIL: the map built from the real-clock recording differs from the drive's"; exit 1; }
echo "the same drive as a real-clock recording builds the same map"
expect2 "parameter 'retime_from_ns': re-times a real-clock recording onto the sim clock; .*drive.db3 was made on the sim clock" \
  "$by" run "$configs/map_build.json" --domain "$domain" --arg recording="$rec" --arg retime_from_ns=5
expect2 "node 'mapper'.*parameter 'track_file': the track is read from the LiDARs' raw returns, and none of the inputs scan0 .. scan3 is wired" \
  "$by" run "$graphs/replay/map_without_scans.json" --domain "$domain" --set lidar_front.file="$rec" --set estimator.file="$rec" \
  --set mapper.track_file="$out/x_track.csv"
expect2 "map build: needs --out DIR" "$by" map build "$rec"
expect2 "map build sets this one itself" "$by" map build "$rec" --out "$out/x" --arg track_file=/tmp/elsewhere.csv
echo "PASS"
