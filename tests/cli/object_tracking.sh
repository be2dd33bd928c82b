#!/usr/bin/env bash
# The object tracker in the main job (tests/graphs/tracking/race_tracked.json, docs/tracking.md):
# 8 s of IMS with three pylons beside the line, on the simulator's LiDARs through the ground
# filter, clustering and the obstacle detector. Every pylon the car passes is a confirmed track
# within 0.5 m of where the world put it, and no track seen for a second (20 frames: a young
# track's speed is still its first frames' noise) moves faster than 1 m/s (nothing on this track
# moves but the car: a track that does is a phantom); each track's path foreseen 3 s ahead (30
# points) ends within 3 m of where it stands.
# usage: object_tracking.sh BRICKYARD CLIENTS GRAPHS DOMAIN OUT
set -u
by=$1; clients=$2; graphs=$3; domain=$4; out=$5
rm -rf "$out"; mkdir -p "$out"
fail() { echo "FAIL: $*"; exit 1; }
"$by" run "$graphs/tracking/race_tracked.json" --domain "$domain" --duration 8 --seed 2 --quiet --progress 0 --no-report \
  --arg 'pylons=[{"s": 120, "d": 5.0}, {"s": 200, "d": -5.0}, {"s": 280, "d": 5.5}]' \
  --record "$out/run.mcap" --record-only 'tracker.tracks,world.world' --record-scene off > "$out/run.log" 2>&1
[ -s "$out/run.mcap" ] || { tail -5 "$out/run.log"; fail "the run did not record"; }
node "$clients/mcap_dump.cjs" "$out/run.mcap" tracker.tracks world.world > "$out/dump.jsonl" || fail "reading the recording"
python3 - "$out/dump.jsonl" <<'PY' || fail "the tracks are not the pylons"
import json, math, sys
tracks, pylons = [], []
for line in open(sys.argv[1]):
    r = json.loads(line)
    if r["topic"] == "world.world" and not pylons:
        pylons = [(p["x"], p["y"]) for p in r["msg"]["pylons"]]
    elif r["topic"] == "tracker.tracks":
        tracks.append(r["msg"]["objects"])
if len(pylons) != 3 or not tracks: sys.exit(f"{len(pylons)} pylons, {len(tracks)} frames of tracks")
fastest = max((o["speed"] for frame in tracks for o in frame if o["age"] >= 20), default=0.0)
if fastest > 1.0: sys.exit(f"a track seen for a second moved at {fastest:.2f} m/s: nothing here moves")
for frame in tracks:
    for o in frame:
        p = o["prediction"]
        if len(p) != 30: sys.exit(f"track {o['id']}: {len(p)} points foreseen, not 30")
        if o["age"] >= 20 and math.hypot(p[-1]["x"] - o["x"], p[-1]["y"] - o["y"]) > 3.0:
            sys.exit(f"track {o['id']}: foreseen {math.hypot(p[-1]['x'] - o['x'], p[-1]['y'] - o['y']):.1f} m away in 3 s, standing")
for k, (x, y) in enumerate(pylons):
    near = [math.hypot(o["x"] - x, o["y"] - y) for frame in tracks for o in frame]
    best = min(near, default=float("inf"))
    if best > 0.5: sys.exit(f"pylon {k} at ({x:.1f}, {y:.1f}): no track within 0.5 m (nearest {best:.2f} m)")
    print(f"pylon {k}: tracked within {best:.2f} m", end="; ")
print(f"{len(tracks)} frames, the fastest track seen for a second {fastest:.2f} m/s")
PY
echo "object_tracking: ok"
