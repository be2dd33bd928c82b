#!/usr/bin/env bash
# A DDS program of another vendor on ROS 2's names (issue 45, docs/ros2.md): tests/ros2/cyclone_peer,
# Cyclone DDS with types compiled by its idlc from `brickyard ros2 idl`, no Brickyard code.
#   writer: it publishes rt/brickyard/src/out (Scalar_) to tests/graphs/ros2/cyclone_source.json,
#           whose sink takes 100 samples, the first 1 to 5, increasing, at 40 to 60 Hz, and ends the run;
#   reader: (with RACE_GRAPH) the main job, transport.naming "ros2", 10 s on the real clock, recorded;
#           the peer reads its estimator's and manager's topics; from the peer's first sample on
#           every sample the recording holds (read by @mcap/core and Foxglove's IDL decoder) is the
#           peer's, in order and equal field for field, none missing, and the first within 2 s.
# Security off (the peer has no identity); discovery on 127.0.0.1 only (CYCLONEDDS_URI).
# usage: ros2_cyclone.sh BRICKYARD PEER CLIENTS SOURCE_GRAPH DOMAIN OUT [RACE_GRAPH]
set -u
by=$1; peer=$2; clients=$3; source_graph=$4; domain=$5; out=$6; race=${7:-}
rm -rf "$out"; mkdir -p "$out"
fail() { echo "FAIL: $*"; exit 1; }
export CYCLONEDDS_URI='<CycloneDDS><Domain id="any"><General><Interfaces><NetworkInterface address="127.0.0.1"/></Interfaces><AllowMulticast>false</AllowMulticast></General><Discovery><ParticipantIndex>auto</ParticipantIndex><MaxAutoParticipantIndex>20</MaxAutoParticipantIndex><Peers><Peer address="127.0.0.1"/></Peers></Discovery></Domain></CycloneDDS>'

"$by" run "$source_graph" --process here --domain "$domain" --duration 30 --progress 0 --no-report --out "$out/source" > "$out/source.log" 2>&1 &
run=$!
"$peer" write "$domain" 150 50 > "$out/writer.log" 2>&1; peer_rc=$?
wait $run; rc=$?
cat "$out/writer.log"
[ $rc = 0 ] || { tail -5 "$out/source.log"; fail "the graph fed by the Cyclone writer: exit $rc"; }
grep -q "node 'check' finished the run" "$out/source.log" || { tail -5 "$out/source.log"; fail "the sink did not end the run"; }
echo "writer: the graph's sink took the Cyclone peer's samples and ended the run"

[ -n "$race" ] || { echo "ros2_cyclone: ok (no race graph: the reader not run)"; exit 0; }
python3 -c "import json,sys; g=json.load(open(sys.argv[1])); g['transport']={'naming':'ros2','security':'off'}; g['clock']={'mode':'real'}; json.dump(g, open(sys.argv[2],'w'))" \
  "$race" "$out/race.json" || exit 1
"$peer" read "$domain" 25 > "$out/peer.jsonl" 2> "$out/reader.log" &
reader=$!
sleep 1
"$by" run "$out/race.json" --domain "$domain" --duration 10 --quiet --progress 0 --no-report --record "$out/race.mcap" \
  --record-only estimator.estimate,manager.command \
  --arg track="$(dirname "$race")/../data/tracks/IMS.csv" > "$out/race.log" 2>&1 || true
wait $reader; reader_rc=$?
cat "$out/reader.log"
[ -s "$out/race.mcap" ] || { tail -5 "$out/race.log"; fail "the race did not record"; }
# 10 s of a two-lap race: it ends at its duration, the laps not done (said so), and nothing else.
grep -q "did not finish: 0 of 2 laps.*(sim 10\.0" "$out/race.log" || { tail -5 "$out/race.log"; fail "the race did not run its 10 s"; }
[ $reader_rc = 0 ] || fail "the Cyclone reader: exit $reader_rc"
node "$clients/mcap_dump.cjs" "$out/race.mcap" estimator.estimate manager.command > "$out/recorded.jsonl" || fail "reading the recording"
python3 - "$out/recorded.jsonl" "$out/peer.jsonl" <<'PY' || fail "the Cyclone reader's samples are not the recording's"
import json, sys
def load(path):
    by = {}
    for line in open(path):
        if line.strip():
            r = json.loads(line)
            by.setdefault(r["topic"], []).append(r["msg"])
    return by
recorded, peer = load(sys.argv[1]), load(sys.argv[2])
for topic in ("estimator.estimate", "manager.command"):
    rec, got = recorded.get(topic, []), peer.get(topic, [])
    if not got: sys.exit(f"{topic}: the peer read nothing ({len(rec)} recorded)")
    first = next((i for i, m in enumerate(rec) if m == got[0]), None)
    if first is None: sys.exit(f"{topic}: the peer's first sample is not in the recording: {got[0]}")
    late = (rec[first]["header"]["stamp_ns"] - rec[0]["header"]["stamp_ns"]) * 1e-9
    if late > 2: sys.exit(f"{topic}: the peer's first sample is {late:.2f} s into the run")
    want = rec[first:]
    for k, (a, b) in enumerate(zip(want, got)):
        if a != b: sys.exit(f"{topic}, sample {first + k}: recorded {a}, the peer read {b}")
    if len(got) != len(want): sys.exit(f"{topic}: the peer read {len(got)} samples from sample {first}, the recording holds {len(want)}")
    print(f"{topic}: {len(got)} samples read by Cyclone DDS, equal to the recording's from sample {first} ({late:.2f} s in) to its last")
PY
echo "ros2_cyclone: ok"
