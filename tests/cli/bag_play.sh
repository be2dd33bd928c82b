#!/usr/bin/env bash
# `brickyard bag play` (docs/recording.md): a recording's topics republished over DDS under their
# own names, at the recorded times; another process hears them with `brickyard topic`: the samples
# it echoes are the recorded ones (time and sequence), and the rate is the recorded rate times
# --rate. Both formats. A file that is not a recording, or is damaged: exit 2.
set -u
by=$1; graphs=$2; domain=$3; out=$4
rm -rf "$out"; mkdir -p "$out"
run="$graphs/localization_double_degradation.json"
"$by" run "$run" --domain "$domain" --quiet --record "$out/rec.db3" || { echo "FAIL: recording (SQLite)"; exit 1; }
"$by" run "$run" --domain "$domain" --quiet --record "$out/rec.mcap" || { echo "FAIL: recording (MCAP)"; exit 1; }
# SQLite: five fixes echoed by another process, each one of the recording's, in order.
"$by" bag play "$out/rec.db3" --domain "$domain" --rate 2 --only 'gnss_left.*' > "$out/play1.log" 2>&1 &
play=$!
"$by" topic echo gnss_left.fix --domain "$domain" --count 5 > "$out/echo.jsonl" 2> "$out/echo.err" || { cat "$out/echo.err"; echo "FAIL: topic echo of a played recording"; exit 1; }
kill -INT $play 2> /dev/null; wait $play 2> /dev/null
python3 - "$out/rec.db3" "$out/echo.jsonl" <<'PY' || exit 1
import json, sqlite3, struct, sys
rows = sqlite3.connect(sys.argv[1]).execute(
    "SELECT m.data FROM messages m JOIN topics t ON t.id = m.topic_id WHERE t.name = 'gnss_left.fix' ORDER BY m.id").fetchall()
recorded = [struct.unpack_from("<qI", d, 4) for (d,) in rows]  # the header: stamp_ns (int64), seq (uint32)
echoed = [(l["header"]["stamp_ns"], l["header"]["seq"]) for l in map(json.loads, open(sys.argv[2]))]
at = recorded.index(echoed[0]) if echoed and echoed[0] in recorded else -1
print(f"bag play (SQLite): echoed {echoed[:2]}…, the recording's fixes {at} to {at + len(echoed) - 1} of {len(recorded)}")
sys.exit(0 if len(echoed) == 5 and at >= 0 and recorded[at:at + 5] == echoed else 1)
PY
# MCAP: the IMU at the recorded 125 Hz, played twice as fast.
"$by" bag play "$out/rec.mcap" --domain "$domain" --rate 2 --only 'imu.*' > "$out/play2.log" 2>&1 &
play=$!
"$by" topic hz imu.imu --domain "$domain" --duration 3 > "$out/hz.txt" 2> "$out/hz.err" || { cat "$out/hz.err"; echo "FAIL: topic hz of a played recording"; exit 1; }
wait $play || { cat "$out/play2.log"; echo "FAIL: bag play (MCAP)"; exit 1; }
tail -1 "$out/hz.txt"
python3 -c "import re,sys; r=float(re.search(r'([0-9.]+) Hz over', open('$out/hz.txt').read().splitlines()[-1]).group(1)); sys.exit(0 if 225 <= r <= 275 else 1)" \
  || { echo "FAIL: the played rate is not 2 x 125 Hz"; exit 1; }
grep -q "bag play: [0-9]* samples of 1 topics" "$out/play2.log" || { cat "$out/play2.log"; echo "FAIL: bag play's summary"; exit 1; }
expect2() {  # pattern, then the command
  pat=$1; shift
  "$@" > "$out/bad.log" 2>&1; rc=$?
  [ $rc -eq 2 ] || { cat "$out/bad.log"; echo "FAIL: exit $rc, expected 2: $*"; exit 1; }
  grep -q -- "$pat" "$out/bad.log" || { cat "$out/bad.log"; echo "FAIL: message lacks '$pat'"; exit 1; }
}
head -c 100000 "$out/rec.mcap" > "$out/cut.mcap"
expect2 "cut.mcap: damaged at byte" "$by" bag play "$out/cut.mcap" --domain "$domain"
echo "junk" > "$out/junk.db3"
expect2 "junk.db3: not a readable recording" "$by" bag play "$out/junk.db3" --domain "$domain"
expect2 "no recorded topic matches --only" "$by" bag play "$out/rec.mcap" --domain "$domain" --only 'nothing.*'
expect2 "--rate: expected a factor of the recorded speed" "$by" bag play "$out/rec.mcap" --rate 0
expect2 "--rate: expected a factor of the recorded speed from 0.001 to 1e6" "$by" bag play "$out/rec.mcap" --rate 1e-300
echo "bag_play: ok"
