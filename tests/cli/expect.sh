#!/usr/bin/env bash
# expect.sh CODE REGEX [ABSENT_REGEX] -- command...
# Passes when the command exits with CODE, its output (stdout+stderr) matches REGEX and, when
# given, does not match ABSENT_REGEX.
code=$1; want=$2; shift 2
absent=""
if [ "$1" != "--" ]; then absent=$1; shift; fi
shift
out=$("$@" 2>&1); rc=$?
echo "$out"
echo "--- exit code $rc (expected $code)"
[ "$rc" -eq "$code" ] || { echo "FAIL: exit code"; exit 1; }
echo "$out" | grep -Ezq -- "$want" || { echo "FAIL: output does not match: $want"; exit 1; }
if [ -n "$absent" ] && echo "$out" | grep -Ezq -- "$absent"; then echo "FAIL: output matches: $absent"; exit 1; fi
exit 0
