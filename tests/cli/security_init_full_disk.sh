#!/usr/bin/env bash
# Issue 44: `security init` that cannot write one of its files (a full disk; here the file-size
# limit, 3 KiB: the governance's signature, 3.1 KB, is the fifth file) exits 1 naming the file and
# leaves no half-made keys folder: a new one is not there at all, an existing one is as it was.
#   security_init_full_disk.sh BY GRAPH OUT
set -u
by=$1; graph=$2; out=$3
rm -rf "$out"; mkdir -p "$out"
limited_init() {  # SIGXFSZ ignored, so the write fails with EFBIG instead of killing the process
  ( trap '' XFSZ; ulimit -f 3; "$by" security init "$graph" --out "$out/keys" ) > "$out/$1.log" 2>&1
}
limited_init fresh; rc=$?
[ $rc -eq 1 ] && grep -q "governance.p7s: cannot be written" "$out/fresh.log" || { cat "$out/fresh.log"; echo "FAIL: exit $rc, the file not named"; exit 1; }
left=$(ls -A "$out" | grep -v '\.log$')
[ -z "$left" ] || { ls -laR "$out"; echo "FAIL: a failed init left: $left"; exit 1; }
echo "a new keys folder: exit 1 naming governance.p7s, nothing left"
"$by" security init "$graph" --out "$out/keys" > "$out/whole.log" 2>&1 || { cat "$out/whole.log"; echo "FAIL: init"; exit 1; }
before=$(cd "$out/keys" && find . -type f -exec sha256sum {} + | sort)
limited_init again; rc=$?
after=$(cd "$out/keys" && find . -type f -exec sha256sum {} + | sort)
[ $rc -eq 1 ] && [ "$before" = "$after" ] && [ -z "$(ls -A "$out" | grep -v '\.log$' | grep -vx keys)" ] \
  || { cat "$out/again.log"; echo "FAIL: an existing keys folder changed, or staging left (exit $rc)"; exit 1; }
echo "an existing keys folder: exit 1, every file as it was"
echo "security_init_full_disk: ok"
