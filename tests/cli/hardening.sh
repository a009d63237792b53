#!/usr/bin/env bash
# hardening.sh HEXCAL DATA CASE: the bounded-input and exit-code guards of
# issue 13 through the real binary (docs/hardening.md). One CTest test per
# CASE (cli/harden_CASE); each case runs several command lines and checks for
# each its exit code (never a signal, never a hang), its message, and that no
# file was written or replaced.
set -u
hexcal=$1 data=$2 case=$3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1
failures=0

# expect CODE REGEX ARGS...: runs hexcal ARGS with a 20 s limit.
expect() {
  local code=$1 regex=$2
  shift 2
  local output rc
  output=$(timeout 20 "$hexcal" "$@" 2>&1)
  rc=$?
  if [ "$rc" -eq 124 ]; then
    echo "FAIL: hung (killed after 20 s): hexcal $*"; failures=$((failures + 1)); return
  fi
  if [ "$rc" -ge 128 ]; then
    echo "FAIL: killed by signal $((rc - 128)): hexcal $*"; echo "$output"; failures=$((failures + 1)); return
  fi
  if [ "$rc" -ne "$code" ]; then
    echo "FAIL: exit code $rc, expected $code: hexcal $*"; echo "$output"; failures=$((failures + 1)); return
  fi
  if ! grep -Eq -- "$regex" <<<"$output"; then
    echo "FAIL: output does not match /$regex/: hexcal $*"; echo "$output"; failures=$((failures + 1)); return
  fi
  echo "ok: hexcal $*"
}

# A file that must keep its bytes: "old" plus its name.
keep() { printf 'old %s\n' "$1" >"$1"; }
unchanged() {
  if [ "$(cat "$1")" != "old $1" ]; then echo "FAIL: $1 was overwritten"; failures=$((failures + 1)); fi
}

R="--robot inria-left-hand"
POSES=$data/poses/inria_sample.csv
REFUSED="exists; use --force to overwrite it"

case $case in
special_files)
  mkfifo robot.yaml legs.csv settings.yaml
  ln -s /dev/zero zero.csv
  ln -s /dev/zero zero.yaml
  expect 2 "robot.yaml.*: not a regular file \(a FIFO\)" robot check ./robot.yaml
  expect 2 "legs.csv: not a regular file \(a FIFO\)" ik $R --poses legs.csv
  expect 2 "settings.yaml: not a regular file \(a FIFO\)" plan $R --settings settings.yaml --out plan.csv
  expect 2 "zero.csv: not a regular file \(a character device\)" calibrate $R --measurements zero.csv --out c.yaml
  expect 2 "zero.yaml: not a regular file \(a character device\)" target check --target zero.yaml
  expect 2 "zero.yaml: not a regular file \(a character device\)" render --camera zero.yaml --poses "$POSES" \
    --out images
  ;;
size_caps)
  # A robot YAML over its 4 MiB cap is refused before it is parsed.
  { echo "# padding"; head -c $((5 * 1024 * 1024)) /dev/zero | tr '\0' '#'; echo; } >big.yaml
  expect 2 "big.yaml.: 5.0 MiB is over the 4.0 MiB limit" robot check ./big.yaml
  expect 2 "big.yaml: 5.0 MiB is over the 4.0 MiB limit" target check --target big.yaml
  ;;
no_overwrite)
  for f in ik.csv cand.csv plan.csv hist.csv cal.yaml sim.csv target.png; do keep $f; done
  expect 2 "ik.csv: $REFUSED" ik $R --poses "$POSES" --out ik.csv
  expect 2 "cand.csv: $REFUSED" candidates $R --count 10 --out cand.csv
  expect 2 "plan.csv: $REFUSED" plan $R --poses 7 --candidate-count 50 --out plan.csv
  expect 2 "hist.csv: $REFUSED" plan $R --poses 7 --candidate-count 50 --out new_plan.csv --history hist.csv
  expect 2 "cal.yaml: $REFUSED" calibrate $R --measurements "$data/measurements/inria_nominal.csv" --out cal.yaml
  expect 2 "sim.csv: $REFUSED" simulate $R --runs 1 --sets random --csv sim.csv
  expect 2 "target.png: $REFUSED" target print --out target.png
  for f in ik.csv cand.csv plan.csv hist.csv cal.yaml sim.csv target.png; do unchanged $f; done
  [ -e new_plan.csv ] && { echo "FAIL: plan wrote --out though --history was refused"; failures=$((failures + 1)); }
  # --force replaces, the same in every command.
  expect 0 "written to ik.csv" ik $R --poses "$POSES" --out ik.csv --force
  expect 0 "written to cand.csv" candidates $R --count 10 --out cand.csv --force
  ;;
count_bounds)
  expect 2 "--poses: 100000 is outside \[8, 500\]" demo --poses 100000 --out demo
  expect 2 "--holdout: 100000 is outside \[0, 500\]" demo --holdout 100000 --out demo
  expect 2 "--poses: -3 is outside" demo --poses -3 --out demo
  expect 2 "--count: 0 is outside" candidates $R --count 0 --out c.csv
  expect 2 "--count: 'many' is not a whole number" candidates $R --count many --out c.csv
  expect 2 "--candidate-count: must be at least 0" plan $R --candidate-count -5 --out p.csv
  expect 2 "--runs: 0 is outside" simulate $R --runs 0
  expect 2 "--runs: 100000000 is outside" simulate $R --runs 100000000
  expect 2 "--poses: 1000000 is outside" simulate $R --poses 1000000
  expect 2 "--sweep: '8:1e300' is not MIN:MAX" simulate $R --sweep 8:1e300
  expect 2 "--threads: 100000 is outside \[0, 256\]" simulate $R --threads 100000
  expect 2 "--threads: -1 is outside \[0, 256\]" render --poses "$POSES" --out r --threads -1
  expect 2 "--threads: 9999 is outside \[0, 256\]" detect --images . --threads 9999
  expect 2 "--threads: 9999 is outside" intrinsics --images . --out cam.yaml --threads 9999
  expect 2 "--threads: 9999 is outside" measure --camera c.yaml --images . --out m.csv --threads 9999
  expect 2 "--min-views: 0 is outside" intrinsics --images . --out cam.yaml --min-views 0
  expect 2 "--dpi: Value 1e6 not in range" target print --out t.png --dpi 1e6
  mkdir in
  awk 'BEGIN { print "x,y,z,q1,q2,q3"; for (i = 0; i < 5001; ++i) print "0,0,50,0,0,0" }' >in/many_poses.csv
  expect 2 "many_poses.csv: 5001 poses, more than the 5000 images render writes at once" render \
    --poses in/many_poses.csv --out r
  leftovers=$(ls -A | grep -v "^in$")
  [ -n "$leftovers" ] && { echo "FAIL: files left behind: $leftovers"; failures=$((failures + 1)); }
  ;;
no_content_leak)
  # A file named by mistake (or on purpose) in place of a robot, a pose table,
  # a target: the error quotes at most a short excerpt, never the file.
  printf 'root:x:0:0:root:/root:/bin/bash\ndaemon:x:1:1:SECRET:/usr/sbin:/usr/sbin/nologin\n' >passwd
  printf 'root:x:0:0:root:/root:/bin/bash/SECRET\nbin:x:2:2:bin:/bin\n' >shadow.csv
  for args in "robot check ./passwd" "fk --robot ./passwd --legs 1,1,1,1,1,1" "ik $R --poses shadow.csv" \
    "target check --target passwd" "render --camera passwd --poses $POSES --out r"; do
    # shellcheck disable=SC2086
    output=$(timeout 20 "$hexcal" $args 2>&1)
    if grep -q SECRET <<<"$output"; then
      echo "FAIL: the error quotes the file: hexcal $args"; echo "$output"; failures=$((failures + 1))
    else
      echo "ok: no content in: $output"
    fi
  done
  expect 2 "found 'root:x:0:0:root:/root:/b\.\.\.'" robot check ./passwd
  ;;
exit_codes)
  # The same fault gives the same code in every command: bad input 2, a failed
  # computation 1 (cli_common.h ExitCodeFor). A robot without a pose box:
  NOBOX="--robot $data/dietmaier-40-real.yaml"
  expect 2 "need limits.pose_box" candidates $NOBOX --kind random --count 5 --out c.csv
  expect 2 "need limits.pose_box" plan $NOBOX --out p.csv
  expect 2 "need limits.pose_box" simulate $NOBOX --runs 1 --sets random
  # Readings in another unit (bad input) against FK that does not converge (failure):
  expect 2 "readings look like mm" fk $R --legs 8.95,24.83,8.90,24.94,8.89,24.94
  expect 2 "readings look like mm" validate $R --measurements "$data/bad_inputs/measurements_wrong_unit.csv"
  expect 2 "readings look like mm" calibrate $R --measurements "$data/bad_inputs/measurements_wrong_unit.csv" \
    --out cal.yaml
  expect 2 "non-positive or non-finite total length" fk $R --legs -100,0,0,0,0,0 --all
  expect 1 "forward kinematics: the pose is at a singularity" fk $R --legs 3.5,0,3.5,0,3.5,0 --start 0,0,60,0,0,0
  printf 'x,y,z,q1,q2,q3,L1,L2,L3,L4,L5,L6\n0,0,45,0,0,0,3.4,0,3.4,0,3.4,0\n' >far.csv
  expect 1 "forward kinematics failed for all 1 measurements" validate $R --measurements far.csv
  # Options out of range are bad input everywhere, also when CLI11 checks them.
  expect 2 "--count: 0 is outside" candidates $R --count 0 --out c.csv
  expect 2 "at least 7 poses" plan $R --poses 6 --out p.csv
  expect 2 "--poses must be at least 7" simulate $R --poses 5
  ;;
*)
  echo "unknown case $case"; exit 2
  ;;
esac
[ "$failures" -eq 0 ] || { echo "$failures failure(s)"; exit 1; }
