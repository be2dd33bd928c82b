#!/usr/bin/env bash
# A graph file, or a file it includes, that is missing, a FIFO (no writer: an open to read would
# wait for ever), a folder, a device or larger than 64 MiB: brickyard validate exits 2 within
# seconds, naming the file and the reason.
#   graph_file_kinds.sh BRICKYARD SCRATCH
set -u
by=$1; out=$2
rm -rf "$out"; mkdir -p "$out"
mkfifo "$out/fifo.json"
mkdir "$out/folder.json"
truncate -s 65M "$out/huge.json"
fail=0
expect_bad() {  # graph file, pattern
  timeout 10 "$by" validate "$1" > "$out/log" 2>&1
  rc=$?
  if [ $rc -ne 2 ] || ! grep -q -- "$2" "$out/log"; then
    echo "FAIL: validate $1: exit $rc (expected 2 and '$2'):"; cat "$out/log"; fail=1
  fi
}
for kind in fifo folder huge; do
  printf '{"include": "%s.json", "nodes": {}}\n' "$kind" > "$out/includes_$kind.json"
done
printf '{"include": "/dev/zero", "nodes": {}}\n' > "$out/includes_device.json"
printf '{"include": "nothing.json", "nodes": {}}\n' > "$out/includes_missing.json"
expect_bad "$out/includes_fifo.json" "includes_fifo.json#/include: included file .*fifo.json: not a regular file"
expect_bad "$out/includes_folder.json" "includes_folder.json#/include: included file .*folder.json: not a regular file"
expect_bad "$out/includes_huge.json" "includes_huge.json#/include: included file .*huge.json: larger than 67108864 bytes"
expect_bad "$out/includes_device.json" "includes_device.json#/include: included file /dev/zero: not a regular file"
expect_bad "$out/includes_missing.json" "includes_missing.json#/include: included file .*nothing.json: does not exist"
expect_bad "$out/fifo.json" "fifo.json: not a regular file"
expect_bad "$out/huge.json" "huge.json: larger than 67108864 bytes"
expect_bad /dev/zero "/dev/zero: not a regular file"
[ $fail -eq 0 ] && echo "graph_file_kinds: ok"
exit $fail
