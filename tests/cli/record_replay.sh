#!/usr/bin/env bash
# Record a simulator run, replay its sensors into the estimator alone, and get the same estimates:
# byte for byte and at the same times. Then the ways it must refuse, each with exit 2 and a
# message naming the culprit.
set -u
by=$1; graphs=$2; domain=$3; out=$4
rm -rf "$out"; mkdir -p "$out"
a="$out/sim.db3"; b="$out/replayed.db3"
"$by" run "$graphs/localization_double_degradation.json" --domain "$domain" --quiet --record "$a" \
  || { echo "FAIL: recording run"; exit 1; }
sets=""; for n in gnss_left gnss_right imu wheels; do sets="$sets --set $n.file=$a"; done
replay="$graphs/replay/estimator_from_recording.json"
"$by" run "$replay" --domain "$domain" --quiet $sets --record "$b" --record-only 'estimator.*' \
  || { echo "FAIL: replay run"; exit 1; }
python3 - "$a" "$b" <<'PY' || exit 1
import sqlite3, sys
def rows(f):
    c = sqlite3.connect(f)
    return list(c.execute("SELECT m.timestamp, m.data FROM messages m JOIN topics t ON t.id = m.topic_id "
                          "WHERE t.name = 'estimator.estimate' ORDER BY m.id"))
a, b = rows(sys.argv[1]), rows(sys.argv[2])
same = sum(1 for x, y in zip(a, b) if x == y)
print(f"estimates: recorded {len(a)}, replayed {len(b)}, identical {same}")
sys.exit(0 if len(a) > 100 and len(a) == len(b) == same else 1)
PY
expect2() {  # pattern, then the command
  pat=$1; shift
  "$@" > "$out/bad.log" 2>&1; rc=$?
  [ $rc -eq 2 ] || { cat "$out/bad.log"; echo "FAIL: exit $rc, expected 2: $*"; exit 1; }
  grep -q -- "$pat" "$out/bad.log" || { cat "$out/bad.log"; echo "FAIL: message lacks '$pat'"; exit 1; }
}
expect2 "sim.db3: exists; a recording is never overwritten" \
  "$by" run "$graphs/localization_double_degradation.json" --domain "$domain" --duration 1 --record "$a"
expect2 "has no topic 'gnss_left.nope' (it has: world.world, car.truth" \
  "$by" run "$replay" --domain "$domain" $sets --set gnss_left.topic=gnss_left.nope
expect2 "topic 'imu.imu' holds brickyard::msgs::Imu, this node replays brickyard::msgs::GnssFix" \
  "$by" run "$replay" --domain "$domain" $sets --set gnss_left.topic=imu.imu
"$by" run "$graphs/real_clock.json" --domain "$domain" --quiet --duration 0.3 --record "$out/real.db3" > /dev/null 2>&1
expect2 "was made on the real clock, this run is on the sim clock" \
  "$by" run "$replay" --domain "$domain" $sets --set gnss_left.file="$out/real.db3" --set gnss_left.topic=src.out
echo "not a database" > "$out/junk.db3"
expect2 "junk.db3" "$by" run "$replay" --domain "$domain" $sets --set gnss_left.file="$out/junk.db3"
expect2 "--record-only: needs --record FILE" "$by" run "$replay" --domain "$domain" $sets --record-only 'x.*'
# A sample cut short (a damaged file whose rows still read): the replay and bag play name the
# recording, the sample and how far into it the bytes still fit the type.
cp "$a" "$out/cut.db3"
python3 - "$out/cut.db3" <<'PY' || exit 1
import sqlite3, sys
c = sqlite3.connect(sys.argv[1])
c.execute("UPDATE messages SET data = substr(data, 1, 30) WHERE id = (SELECT min(m.id) FROM messages m "
          "JOIN topics t ON t.id = m.topic_id WHERE t.name = 'gnss_left.fix')")
c.commit()
PY
expect2 "cut.db3: sample 0 of 'gnss_left.fix' does not decode as brickyard::msgs::GnssFix: its first [0-9]* of 30 bytes decode, the next do not" \
  "$by" run "$replay" --domain "$domain" $sets --set gnss_left.file="$out/cut.db3"
expect2 "cut.db3: sample 0 of gnss_left.fix does not decode as brickyard::msgs::GnssFix: .* at byte [0-9]* of 30" \
  "$by" bag play "$out/cut.db3" --domain "$domain" --only 'gnss_left.*'
# Stamps that are no time (one row at INT64_MIN, one a string): bag info refuses the recording,
# counting them and naming the first (it showed a span of -9223372036.855 s).
cp "$a" "$out/bad_stamps.db3"
python3 - "$out/bad_stamps.db3" <<'PY' || exit 1
import sqlite3, sys
c = sqlite3.connect(sys.argv[1])
c.execute("UPDATE messages SET timestamp = -9223372036854775808 WHERE id = 5")
c.execute("UPDATE messages SET timestamp = 'soon' WHERE id = 9")
c.commit()
PY
expect2 "bad_stamps.db3: 2 messages stamped with no time (negative, or not whole nanoseconds), the first message 5" \
  "$by" bag info "$out/bad_stamps.db3"
# brickyard bag info: the recording's topics, types and counts as the file holds them.
"$by" bag info "$a" --json > "$out/info.json" || { echo "FAIL: bag info"; exit 1; }
python3 - "$a" "$out/info.json" <<'PY' || exit 1
import json, sqlite3, sys
info = json.load(open(sys.argv[2]))
c = sqlite3.connect(sys.argv[1])
want = {n: (t, k) for n, t, k in c.execute(
    "SELECT t.name, t.type, count(m.id) FROM topics t LEFT JOIN messages m ON m.topic_id = t.id GROUP BY t.id")}
got = {t["name"]: (t["type"], t["count"]) for t in info["topics"]}
total = sum(k for _, k in want.values())
print(f"bag info: {len(got)} topics, {info['messages']} samples, {info['end_s']:.3f} s")
sys.exit(0 if got == want and info["messages"] == total and info["clock"] == "sim" and total > 1000 else 1)
PY
"$by" bag info "$a" | grep -q "^estimator.estimate  *brickyard::msgs::LocalizationEstimate" || { echo "FAIL: bag info's table"; exit 1; }
expect2 "junk.db3: not a readable recording: file is not a database" "$by" bag info "$out/junk.db3"
expect2 "nope.db3: no such file" "$by" bag info "$out/nope.db3"
echo "record_replay: ok"
