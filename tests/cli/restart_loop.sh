#!/usr/bin/env bash
# How often a restarted writer is heard again (docs/reliability.md): N supervised runs of
# tests/graphs/multiprocess/supervised.json, process a killed with SIGKILL at 2.1 to 2.9 s and
# restarted; prints, per run, the kill time and b's count (300: a's samples came back; less: the
# restarted a was never heard). Run it in a private network namespace:
#   unshare -n bash -c "ip link set lo up; tests/cli/restart_loop.sh build/bin/brickyard 8 true"
# usage: restart_loop.sh BRICKYARD RUNS SHARED_MEMORY(true|false) [DOMAIN]
set -u
by=$1; runs=$2; shm=$3; domain=${4:-90}
graph=$(dirname "$0")/../graphs/multiprocess/supervised.json
for i in $(seq 1 "$runs"); do
  out=/tmp/restart_loop_$i; rm -rf "$out"
  at=2.$(( (i * 13) % 10 ))
  "$by" run "$graph" --domain "$domain" --progress 0 --set check.finish_after=300 --duration 12 --arg shared_memory="$shm" \
    --out "$out" > "$out.log" 2>&1 &
  sup=$!
  sleep "$at"
  kill -9 "$(pgrep -f -- "--process a --domain $domain --out $out/a" | head -1)"
  wait $sup
  python3 -c "import json,sys; print(sys.argv[1], json.load(open(sys.argv[2]))['nodes']['check']['metrics']['count'])" "$at" "$out/b/summary.json"
done
