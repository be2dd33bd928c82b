#!/usr/bin/env bash
# The split race attacked from the same machine (issue 44's targets: a foreign participant with
# any name reads no sample and has no forged sample obeyed; no control value readable on the wire
# or in /dev/shm). The main job split over two processes (tests/graphs/multiprocess/
# ims_race_split.json) on the real clock, supervised, secured by default. While it races:
# 1. an eavesdropper: sniff_loopback.py captures every UDP payload on loopback and the pages of
#    every new Fast DDS shared-memory file for 8 s, while the graph's observer identity reads the
#    commands the car is driven by (manager.command); every distinctive double of those commands
#    is searched for in the capture (race_attacked.py): none may be found;
# 2. a stranger: `topic echo manager.command` with no identity reads nothing;
# 3. a forger named as the stack's process (`bag play --identity stack`, no keys) plays 6 s of
#    manager.command: one writer only (the stack's manager) may feed the car's commands.
# The same with "security": "off" must show the plaintext and the forged commands taken (else
# these checks could not see them, and prove nothing). Over shared memory (the default between
# processes on one machine) and over UDP only.
# Exit 77 (skipped) where no packet can be captured (no network namespace of its own, not root).
# usage: race_attacked.sh BRICKYARD GRAPH DOMAIN OUT
set -u
by=$1; graph=$2; domain=$3; out=$4
here=$(dirname "$0")
rm -rf "$out"; mkdir -p "$out"
fail() { echo "FAIL: $*"; exit 1; }

# The forger's commands: the first 6 s of the race in one process on the sim clock.
"$by" run "$graph" --one-process --arg clock=sim --domain "$domain" --duration 6 --quiet --progress 0 --no-report \
  --record "$out/forged.mcap" --record-only manager.command > "$out/forged.log" 2>&1
"$by" bag info "$out/forged.mcap" > "$out/forged.info" 2>&1 || { cat "$out/forged.log"; fail "recording the forger's commands"; }

# Races GRAPH as MODE (a name) with the options after it, attacked once it runs.
race() {
  local mode=$1; shift
  ls /dev/shm > "$out/$mode.shm_before"
  "$by" run "$graph" --domain "$domain" --duration 60 --progress 0 --no-report --out "$out/$mode" "$@" 2> "$out/$mode.log" &
  local sup=$!
  for _ in $(seq 1 300); do
    grep -q "\[stack\] .*running" "$out/$mode.log" && grep -q "\[sim\] .*running" "$out/$mode.log" && break
    sleep 0.1
  done
  sleep 2
  local keys
  keys=$(sed -n 's/.*for the graph in \(.*\) ("off" turns this off.*/\1/p' "$out/$mode.log" | head -n 1)
  python3 "$here/sniff_loopback.py" 8 "$out/$mode" "$out/$mode.shm_before" > "$out/$mode.sniff.log" 2>&1 &
  local sniff=$!
  "$by" topic echo manager.command --domain "$domain" --duration 8 ${keys:+--security "$keys"} > "$out/$mode.commands" 2> "$out/$mode.echo.log"
  if [ -n "$keys" ]; then
    "$by" topic echo manager.command --domain "$domain" --duration 3 > "$out/$mode.stranger" 2>&1 \
      && fail "$mode: a reader with no identity read manager.command: $(head -c 200 "$out/$mode.stranger")"
  fi
  wait $sniff; local rc=$?
  if [ $rc = 77 ]; then cat "$out/$mode.sniff.log"; kill -INT $sup; wait $sup; exit 77; fi  # skipped: said
  [ $rc = 0 ] || { cat "$out/$mode.sniff.log"; fail "$mode: the capture failed"; }
  # After the capture: the forger's own samples are plaintext whatever the run's security.
  "$by" bag play "$out/forged.mcap" --domain "$domain" --identity stack > "$out/$mode.forger.log" 2>&1
  kill -INT $sup 2>/dev/null; wait $sup
  echo "$mode: $(cat "$out/$mode.sniff.log"); keys: ${keys:-none}"
}

# Stopped mid-race: the simulator's referee says the race did not finish (and the stack, that its
# peer failed so); any other end (a process that died, a peer gone silent) fails this test.
raced_until_stopped() {
  local mode=$1
  grep -q "process 'sim' .*exited with code 1: node 'referee' (sim.referee): did not finish" "$out/$mode.log" \
    && ! grep -E "^\[brickyard\] process .*(exited|killed|crashed)" "$out/$mode.log" | grep -v -q "did not finish" \
    || { tail -5 "$out/$mode.log"; fail "$mode: the run did not race until it was stopped"; }
}

for shm in true false; do
  race "secured_shm_$shm" --arg shared_memory=$shm
  grep -q "authenticated and their traffic encrypted" "$out/secured_shm_$shm.log" || { cat "$out/secured_shm_$shm.log"; fail "the run did not say it is secured"; }
  raced_until_stopped "secured_shm_$shm"
  # Off, the forged commands are obeyed: the car may leave the track, and the run end otherwise.
  race "off_shm_$shm" --arg shared_memory=$shm --arg security=off
  python3 "$here/race_attacked.py" "$out/secured_shm_$shm" "$out/off_shm_$shm" || exit 1
done
echo "race_attacked: ok"
