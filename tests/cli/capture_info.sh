#!/usr/bin/env bash
# `brickyard capture info` on every shipped capture, its numbers held against the captures read
# on their own and the decoders' unit tests (capture_info.py).
set -u
by=$1; data=$2; out=$3
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$out"; mkdir -p "$out"
python3 "$here/capture_logs.py" "$out" || { echo "FAIL: making the GNSS logs"; exit 1; }
python3 "$here/capture_info.py" "$by" "$data" "$out"
