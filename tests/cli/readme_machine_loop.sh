#!/usr/bin/env bash
# readme_machine_loop.sh HEXCAL: the README's "A robot and a camera in the
# loop" block, run as written (issue 33): the default plan, the default
# options, LinuxCNC's simulated hexapod on port 5007 and `hexcal sim-camera`,
# then calibrate, verify and export --push. The block is taken from README.md
# itself, so the test follows the README: the one change is its machine
# folder, /tmp/machine, which becomes a folder of this test. It runs in a
# temporary folder (build/app/hexcal and scripts/ there are links to this
# build's binary and the tree's scripts), so nothing is left in the tree.
# `export --push` asks the operator to type y at a terminal: the block runs
# under script(1) with "y" as its typed input.
# Then: every one of the plan's 16 poses acquired, the calibration's verdict
# not poor and its held-out error not poor, and `verify` after the push at least
# 5 times closer than before it (position RMS, issue 33). Skipped (77) without LinuxCNC or Aravis in this build, when
# another LinuxCNC runs on the host, or when port 5007 is taken.
set -eu
hexcal=$(realpath "$1")
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
if "$hexcal" sim-camera --session /nonexistent --machine-robot x 2>&1 |
  grep -q "built without Aravis"; then echo "hexcal was built without Aravis: skipped"; exit 77; fi
. "$here/linuxcnc_common.sh"
if (exec 3<>/dev/tcp/127.0.0.1/5007) 2>/dev/null; then
  echo "port 5007 (the README's linuxcncrsh port) is taken: skipped"; exit 77
fi

. "$here/readme_block.sh"
readme_block "## A robot and a camera in the loop" /tmp/machine "$dir/machine" >"$dir/block.sh"
grep -q "hexcal acquire" "$dir/block.sh"
readme_workdir "$dir/work" "$hexcal"
cd "$dir/work"
start=$(date +%s.%N)
code=0
printf 'y\n' | script -qefc "bash -eu $dir/block.sh" /dev/null >"$dir/out" 2>&1 || code=$?
end=$(date +%s.%N)
[ "$code" -eq 0 ] || { tr -d '\r' <"$dir/out"; echo "the README's block failed (exit $code)"; exit 1; }
tr -d '\r' <"$dir/out" >"$dir/log"
grep -q "16 recorded, 0 already recorded, 0 failed, of 16 poses" "$dir/log" ||
  { cat "$dir/log"; echo "acquire did not record the 16 poses"; exit 1; }
[ "$(tail -n +2 run1/legs.csv | wc -l)" -eq 16 ]
# The verdict of the README's plan is at best "acceptable": 12 calibration
# images (16, every fourth held out) are fewer than a "good" 21. What the
# calibration achieved is the held-out error: good in most runs (0.0017 to
# 0.0049 cm = 0.3 to 1× the noise-predicted error), once 2.1× (0.0107 cm, one
# held-out image off) in a full-suite run, so "not poor" (a frame that shows
# the previous pose gives 0.39 cm, 77×: poor); what the calibration is worth
# to the machine is checked by verify after the push below.
grep -Eq "^Verdict: (good|acceptable)" "$dir/log" && grep -Eq "^  (good      |acceptable) held-out error" "$dir/log" ||
  { cat "$dir/log"; echo "the calibration's verdict is poor, or its held-out error is poor"; exit 1; }
grep -q "pushed 61 pins into the running LinuxCNC and homed again" "$dir/log" || { cat "$dir/log"; exit 1; }
python3 - "$dir/log" <<'PY' || { cat "$dir/log"; exit 1; }
import re, sys
rms = [float(v) for v in re.findall(r"^commanded against seen: position RMS ([0-9.e+-]+)", open(sys.argv[1]).read(), re.M)]
assert len(rms) == 2, rms
print("verify before and after the push: position RMS %.5f -> %.5f (%.1f times closer)" % (rms[0], rms[1], rms[0] / rms[1]))
assert rms[1] * 5 <= rms[0], rms
PY
sed 's/.*\] [0-9]*% ([0-9/]*)//' "$dir/log" |
  grep -E "recorded, |^held-out validation|^Verdict|held-out error|commanded against seen|pushed|^\[JOINT_0\] HOME "
python3 -c "import sys; print('README machine loop: ok in %.0f s' % (float(sys.argv[2]) - float(sys.argv[1])))" \
  "$start" "$end"
