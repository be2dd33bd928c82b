#!/usr/bin/env bash
# configs/sim_truth_lap.json: at least 3 IMS laps, top speed >= 60 m/s, no wall contact, every
# sensor publishing. Prints the real-time factor (a figure, not a check: speed lives in bench/).
set -u
by=$1; graph=$2; domain=$3; out=$4
rm -rf "$out"
"$by" run "$graph" --domain "$domain" --quiet --out "$out"; rc=$?
s="$out/summary.json"
[ $rc -eq 0 ] || { echo "FAIL: exit $rc"; exit 1; }
num() { grep -o "\"$1\": [-0-9.e+]*" "$s" | head -1 | awk '{print $2}'; }
laps=$(num laps_completed); top=$(num max_speed_mps); contacts=$(num wall_contacts)
sim=$(num sim_time_s); wall=$(num wall_time_s)
echo "laps $laps, top speed $top m/s, wall contacts $contacts, sim $sim s in $wall s wall"
awk -v l="$laps" -v t="$top" -v c="$contacts" 'BEGIN { exit !(l >= 3 && t >= 60 && c == 0) }' || { echo "FAIL: laps/speed/contacts"; exit 1; }
for n in gnss_left gnss_right imu wheels lidar_front lidar_left lidar_right; do
  grep -q "\"$n\": {" "$s" || { echo "FAIL: no node $n"; exit 1; }
done
[ "$(grep -c '"published": 0' "$s")" -eq 0 ] || { echo "FAIL: an output published nothing"; exit 1; }
echo "sim_truth_lap: ok"
