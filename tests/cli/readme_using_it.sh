#!/usr/bin/env bash
# readme_using_it.sh HEXCAL: the README's "Using it" block, run as written
# (issue 39). It starts from `hexcal demo --out example` and every later
# command reads only what an earlier one wrote, so it runs in an empty
# temporary folder where build/app/hexcal is a link to this build's binary
# (readme_block.sh): a command that needs a file the block never made fails.
# Fails on any command's non-zero exit, and when the block writes into build/
# (the demo session `make demo` leaves there is the showcase, not a scratch
# folder).
set -eu
hexcal=$(realpath "$1")
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
. "$here/readme_block.sh"
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
readme_block "## Using it" >"$dir/block.sh"
grep -q "hexcal demo --out example" "$dir/block.sh"
readme_workdir "$dir/work" "$hexcal"
cd "$dir/work"
start=$(date +%s.%N)
code=0
# -x: the log shows each command before its output, so a failure names it.
bash -euo pipefail -x "$dir/block.sh" >"$dir/log" 2>&1 || code=$?
end=$(date +%s.%N)
[ "$code" -eq 0 ] || { cat "$dir/log"; echo "the README's \"Using it\" block failed (exit $code)"; exit 1; }
[ "$(ls build)" = app ] && [ "$(ls build/app)" = hexcal ] ||
  { ls -R build; echo "the README's \"Using it\" block wrote into build/"; exit 1; }
# The verdicts the README explains, command by command (the output of each
# follows its "+ build/app/hexcal ..." line of the trace).
python3 - "$dir/log" <<'PY' || { cat "$dir/log"; echo "a verdict is not the one the README explains"; exit 1; }
import re, sys
chunks = re.split(r"^\+ (build/app/hexcal .*)$", open(sys.argv[1]).read(), flags=re.M)
verdicts = []
for command, output in zip(chunks[1::2], chunks[2::2]):
    found = re.findall(r"^Verdict: (\w+)", output, re.M)
    verdicts.append((command, found[-1] if found else None))
    print("%-8s %s" % (found[-1] if found else "", command[:120]))
expected = [("demo --out example", "good"), ("validate --robot inria-left-hand", "poor"),
            ("validate --robot calibrated.yaml", "good"), ("calibrate --session example", "good"),
            ("demo --poses 64", "poor")]
for part, level in expected:
    got = [v for c, v in verdicts if part in c]
    assert got == [level], "%s: verdicts %s, the README says %s" % (part, got, level)
PY
python3 -c "import sys; print('README \"Using it\": ok in %.0f s' % (float(sys.argv[2]) - float(sys.argv[1])))" \
  "$start" "$end"
