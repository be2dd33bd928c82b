#!/usr/bin/env bash
# A plain Fast DDS program that knows nothing of Brickyard subscribes to a wire's topic.
set -u
by=$1; sub=$2; graph=$3; domain=$4
"$by" run "$graph" --domain "$domain" --duration 4 --quiet &
pid=$!
"$sub" "$domain" brickyard/double/out 20 6
rc=$?
wait $pid || { echo "FAIL: brickyard run failed"; exit 1; }
exit $rc
