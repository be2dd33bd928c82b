#!/usr/bin/env bash
# A process killed with SIGKILL outside any supervisor leaves its 16 MiB Fast DDS segment in
# /dev/shm (nothing of it can run); the next run on the machine removes it, says so, and leaves
# every live process's segment alone.
#   shm_reclaimed.sh BRICKYARD GRAPH(real clock) DOMAIN SCRATCH
set -u
by=$1; graph=$2; domain=$3; out=$4
rm -rf "$out"; mkdir -p "$out"
segments() { ls /dev/shm | grep -E '^fastrtps_[0-9a-f]{16}$' | sort; }
before=$(segments)
# A live run beside, started first (a run's start reclaims what is dead): its segment must stay.
"$by" run "$graph" --domain $((domain + 1)) --duration 10 --quiet --progress 0 > "$out/live.log" 2>&1 &
live=$!
sleep 1
live_segment=$(comm -13 <(echo "$before") <(segments) | head -1)
"$by" run "$graph" --domain "$domain" --duration 30 --quiet --progress 0 > "$out/killed.log" 2>&1 &
victim=$!
sleep 2
left=$(comm -13 <(echo "$before"; echo "$live_segment") <(segments))
kill -9 $victim; wait $victim 2> /dev/null
[ -n "$left" ] || { echo "FAIL: the killed run made no segment to leave"; kill $live; exit 1; }
sleep 1  # the killed run's lock file now older than the 2 s a new participant may take to lock its own
"$by" run "$graph" --domain "$domain" --duration 0.5 --progress 0 > "$out/next.log" 2>&1
rc=$?
[ $rc -eq 0 ] || { cat "$out/next.log"; echo "FAIL: the next run: exit $rc"; kill $live; exit 1; }
for s in $left; do
  [ ! -e "/dev/shm/$s" ] && [ ! -e "/dev/shm/${s}_el" ] || { echo "FAIL: $s is still in /dev/shm"; kill $live; exit 1; }
done
grep -qE "notice: removed [0-9]+ shared-memory segments? \([0-9.]+ MB\) that processes which died had left in /dev/shm" "$out/next.log" \
  || { cat "$out/next.log"; echo "FAIL: the removal was not said"; kill $live; exit 1; }
[ -n "$live_segment" ] && [ -e "/dev/shm/$live_segment" ] || { echo "FAIL: a live run's segment $live_segment was removed"; kill $live; exit 1; }
wait $live || { cat "$out/live.log"; echo "FAIL: the live run beside failed"; exit 1; }
echo "shm_reclaimed: the killed run's $(echo $left | wc -w) segment(s) removed by the next run; the live run's kept"
