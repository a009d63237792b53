#!/usr/bin/env bash
# expect.sh EXIT_CODE REGEX -- COMMAND...
# Runs COMMAND as a user would and checks its exit code, that stdout+stderr
# match REGEX (extended grep), and that it was not killed by a signal.
set -u
expected_code=$1 regex=$2
shift 3
output=$("$@" 2>&1)
code=$?
if [ "$code" -ge 128 ]; then
  echo "FAIL: killed by signal $((code - 128)): $*"; echo "$output"; exit 1
fi
if [ "$code" -ne "$expected_code" ]; then
  echo "FAIL: exit code $code, expected $expected_code: $*"; echo "$output"; exit 1
fi
if ! grep -Eq -- "$regex" <<<"$output"; then
  echo "FAIL: output does not match /$regex/: $*"; echo "$output"; exit 1
fi
echo "ok: $*"
