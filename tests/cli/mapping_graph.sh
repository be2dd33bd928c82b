#!/usr/bin/env bash
# configs/map_ims.json for its first 12 s (issue 17): the scan mapper registers the frames onto
# the map it builds, its pose stays near the truth (the scorer, the simulator's), and the map is
# written as a PCD file that holds what the summary says.
#   mapping_graph.sh BRICKYARD GRAPH DOMAIN OUT
set -u
by=$1; graph=$2; domain=$3; out=$4
rm -rf "$out"; mkdir -p "$out"
"$by" run "$graph" --domain "$domain" --quiet --no-report --duration 12 --arg laps=0 --arg "map_file=$out/map.pcd" --out "$out/run"; rc=$?
[ $rc -eq 0 ] || { echo "FAIL: exit $rc"; exit 1; }
python3 - "$out/run/summary.json" "$out/map.pcd" <<'PY'
import json, sys
s = json.load(open(sys.argv[1])); m = s["nodes"]["mapper"]["metrics"]; sc = s["nodes"]["score_mapper"]["metrics"]
head = open(sys.argv[2], "rb").read(400).split(b"DATA binary\n")[0].decode()
points = int([l for l in head.splitlines() if l.startswith("POINTS")][0].split()[1])
print("frames %d, registered %d, keyframes %d, map %d voxels (file %d points), mapper rmse %.3f m, max %.3f m"
      % (m["frames"], m["registered"], m["keyframes"], m["map_voxels"], points, sc["rmse_m"], sc["max_error_m"]))
ok = m["frames"] >= 200 and m["registered"] >= 0.95 * (m["frames"] - 1) and points == m["map_voxels"] > 0 and sc["rmse_m"] < 0.1
print("mapping: %s" % ("ok" if ok else "FAIL")); sys.exit(0 if ok else 1)
PY
