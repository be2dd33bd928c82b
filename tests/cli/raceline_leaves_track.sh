#!/usr/bin/env bash
# A racing line file that leaves the track: Spielberg's line (data/racelines, TUM
# racetrack-database, LGPL-3.0) with 9 of its points moved 30 m, given to both planners. Each must
# refuse it naming the file and the point — before this, keep_inside pulled the points in and the
# car followed the kink into the wall.
#   raceline_leaves_track.sh EXPECT BRICKYARD SOURCE_DIR DOMAIN OUT
set -u
expect=$1; by=$2; src=$3; domain=$4; out=$5
mkdir -p "$out"
line="$out/raceline_leaves_track.csv"
python3 - "$src/data/racelines/Spielberg.csv" "$line" <<'PY'
import sys
rows = [l for l in open(sys.argv[1]) if not l.startswith('#')]
with open(sys.argv[2], 'w') as f:
    f.write('# x_m,y_m\n')
    for i, l in enumerate(rows):
        x, y = map(float, l.split(','))
        f.write('%f,%f\n' % (x, y + (30 if 100 < i < 110 else 0)))
PY
"$expect" 1 "raceline_leaves_track.csv.*the line leaves the track: point" "\[brickyard\] success" -- \
  "$by" run "$src/configs/race.json" --domain "$domain" --no-report --out "$out/road_graph" --duration 5 \
  --arg track=tracks/Spielberg.csv --arg wall_side=left --set "planner.raceline=$line" || exit 1
# planning.racing_line (configs/ims_resilient.json) on Spielberg, as the line is.
"$expect" 1 "raceline_leaves_track.csv: the line leaves the track: point" "\[brickyard\] success" -- \
  "$by" run "$src/configs/ims_resilient.json" --domain "$domain" --no-report --out "$out/racing_line" --duration 5 \
  --set world.track=tracks/Spielberg.csv --set map.track=tracks/Spielberg.csv --set "racing_line.raceline=$line"
