#!/usr/bin/env bash
# MCAP recordings (docs/recording.md), read by Foxglove's own libraries: the same run recorded as
# MCAP and as SQLite holds the same samples, byte for byte and at the same times, every message
# decoded by Foxglove's OMG IDL decoder; lz4 and uncompressed chunks too; the replay plugin and
# `bag info` read MCAP; a cut or corrupted file is read up to the damage and refused (exit 2,
# the file and the byte named).
set -u
by=$1; graphs=$2; domain=$3; out=$4; clients=$5
rm -rf "$out"; mkdir -p "$out"
check="node $clients/mcap_check.cjs"
run="$graphs/localization_double_degradation.json"
"$by" run "$run" --domain "$domain" --quiet --record "$out/a.mcap" || { echo "FAIL: recording run (MCAP)"; exit 1; }
"$by" run "$run" --domain "$domain" --quiet --record "$out/a.db3" || { echo "FAIL: recording run (SQLite)"; exit 1; }
$check "$out/a.mcap" --last estimator.estimate > "$out/a.json" || { echo "FAIL: @mcap/core or the decoder refused a.mcap"; exit 1; }
python3 - "$out/a.db3" "$out/a.json" <<'PY' || exit 1
import hashlib, json, sqlite3, struct, sys
got = json.load(open(sys.argv[2]))
c = sqlite3.connect(sys.argv[1])
want = {}
for name, typ in c.execute("SELECT name, type FROM topics ORDER BY id"):
    h, n = hashlib.sha256(), 0
    for t, d in c.execute("SELECT m.timestamp, m.data FROM messages m JOIN topics t ON t.id = m.topic_id WHERE t.name = ? ORDER BY m.id", (name,)):
        h.update(struct.pack("<Q", t)); h.update(d); n += 1
    want[name] = {"schema": typ, "count": n, "sha256": h.hexdigest()}
same = sum(1 for k in want if got["topics"].get(k) == want[k])
wires = [k for k, v in got["topics"].items() if not v["schema"].startswith("foxglove.")]  # a .db3 holds no scene
scene = len(got["topics"]) - len(wires)
print(f"MCAP against SQLite: {len(wires)} wires (and {scene} scene channels), {got['messages']} messages decoded; {same} of {len(want)} topics identical")
last = got.get("last", {})
ok = same == len(want) == len(wires) and scene >= 2 and got["messages"] > 1000 and got["metadata"]["brickyard"]["clock"] == "sim"
ok = ok and isinstance(last.get("header", {}).get("stamp_ns"), int) and isinstance(last.get("x"), float) and len(last.get("covariance", [])) == 9
sys.exit(0 if ok else 1)
PY
for how in lz4 none; do
  "$by" run "$run" --domain "$domain" --quiet --record "$out/$how.mcap" --record-compression "$how" \
    || { echo "FAIL: recording run ($how)"; exit 1; }
  $check "$out/$how.mcap" > "$out/$how.json" || { echo "FAIL: @mcap/core refused $how.mcap"; exit 1; }
done
# The replay plugin on the MCAP file: the same estimates as recorded.
sets=""; for n in gnss_left gnss_right imu wheels; do sets="$sets --set $n.file=$out/a.mcap"; done
replay="$graphs/replay/estimator_from_recording.json"
"$by" run "$replay" --domain "$domain" --quiet $sets --record "$out/replayed.db3" --record-only 'estimator.*' \
  || { echo "FAIL: replay from MCAP"; exit 1; }
python3 - "$out/a.db3" "$out/replayed.db3" <<'PY' || exit 1
import sqlite3, sys
def rows(f):
    return list(sqlite3.connect(f).execute("SELECT m.timestamp, m.data FROM messages m JOIN topics t ON t.id = m.topic_id "
                                           "WHERE t.name = 'estimator.estimate' ORDER BY m.id"))
a, b = rows(sys.argv[1]), rows(sys.argv[2])
same = sum(1 for x, y in zip(a, b) if x == y)
print(f"replayed from MCAP: {len(b)} estimates, {same} identical to the recorded {len(a)}")
sys.exit(0 if len(a) > 100 and len(a) == len(b) == same else 1)
PY
# bag info: the counts Foxglove's reader found.
"$by" bag info "$out/a.mcap" --json > "$out/info.json" || { echo "FAIL: bag info on MCAP"; exit 1; }
python3 - "$out/info.json" "$out/a.json" <<'PY' || exit 1
import json, sys
info, ref = json.load(open(sys.argv[1])), json.load(open(sys.argv[2]))
got = {t["name"]: (t["type"], t["count"]) for t in info["topics"]}
want = {k: (v["schema"], v["count"]) for k, v in ref["topics"].items()}
sys.exit(0 if got == want and info["messages"] == ref["messages"] and info["clock"] == "sim" else 1)
PY
expect2() {  # pattern, then the command
  pat=$1; shift
  "$@" > "$out/bad.log" 2>&1; rc=$?
  [ $rc -eq 2 ] || { cat "$out/bad.log"; echo "FAIL: exit $rc, expected 2: $*"; exit 1; }
  grep -q -- "$pat" "$out/bad.log" || { cat "$out/bad.log"; echo "FAIL: message lacks '$pat'"; exit 1; }
}
# Cut short (a disk that filled, a copy stopped half-way), and a chunk's bytes changed.
size=$(stat -c %s "$out/a.mcap")
head -c $((size * 3 / 5)) "$out/a.mcap" > "$out/cut.mcap"
expect2 "cut.mcap: damaged at byte [0-9]*: a record (opcode 6) of [0-9]* bytes runs past the end of the file" "$by" bag info "$out/cut.mcap"
grep -q "^estimator.estimate" "$out/bad.log" || { echo "FAIL: bag info did not show what it read before the damage"; exit 1; }
expect2 "cut.mcap: damaged at byte" "$by" run "$replay" --domain "$domain" $sets --set imu.file="$out/cut.mcap"
python3 - "$out/a.mcap" "$out/flipped.mcap" <<'PY'
import sys
b = bytearray(open(sys.argv[1], "rb").read())
for i in range(len(b) // 2, len(b) // 2 + 64): b[i] ^= 0x5a
open(sys.argv[2], "wb").write(b)
PY
expect2 "flipped.mcap: damaged at byte [0-9]*: a chunk" "$by" bag info "$out/flipped.mcap"
expect2 "--record-compression brotli: expected zstd, lz4 or none" "$by" run "$run" --record "$out/x.mcap" --record-compression brotli
expect2 "a.mcap: exists; a recording is never overwritten" "$by" run "$run" --domain "$domain" --duration 1 --record "$out/a.mcap"
echo "mcap_recording: ok"
