#!/usr/bin/env bash
# `brickyard run --out DIR` onto a full disk (issue 20): exit 1 naming the file that could not be
# written, and nothing half-written left behind — a summary.json whole (it parses) or absent, the
# recording cut short kept as recording.mcap.part, never under its own name. The disk is a
# 192 KiB tmpfs mounted in a mount namespace of the test's own (unshare -m, or -rm as a user);
# exit 77 (skipped) where the platform allows neither.
set -u
by=$(realpath "$1"); graph=$(realpath "$2"); domain=$3; out=$4
if [ "${BY_MOUNT_NS:-0}" != 1 ]; then
  for flags in -m -rm; do
    unshare $flags true 2> /dev/null && exec env BY_MOUNT_NS=1 unshare $flags -- "$0" "$@"
  done
  echo "SKIP: no mount namespace here"; exit 77
fi
rm -rf "$out"; mkdir -p "$out/disk"
mount -t tmpfs -o size=192k tmpfs "$out/disk" 2> "$out/mount.err" || { cat "$out/mount.err"; echo "SKIP: cannot mount a tmpfs"; exit 77; }
fail() { echo "FAIL: $*"; umount "$out/disk"; exit 1; }
# The recording under --out fills the disk within the run.
"$by" run "$graph" --domain "$domain" --quiet --duration 20 --out "$out/disk/run" > "$out/run.log" 2>&1; rc=$?
cat "$out/run.log"
[ $rc -eq 1 ] || fail "exit $rc on a full disk, expected 1"
grep -q "$out/disk/run/[a-z.]*[: ].*No space left on device\|$out/disk/run/[a-z.]*: .*database or disk is full" "$out/run.log" \
  || fail "the message names no file under --out with the disk full"
ls -la "$out/disk/run"
# The recording cut short by the full disk is kept under its temporary name, never as a whole one.
[ ! -e "$out/disk/run/recording.mcap" ] || fail "a recording cut short took the name of a whole one"
[ -z "$(find "$out/disk" -name '*.part' ! -name 'recording.mcap.part')" ] || fail "a .part file other than the recording's was left"
if [ -e "$out/disk/run/summary.json" ]; then
  python3 -c 'import json,sys; json.load(open(sys.argv[1]))' "$out/disk/run/summary.json" || fail "a half-written summary.json"
fi
umount "$out/disk"
echo "out_full_disk: ok"
