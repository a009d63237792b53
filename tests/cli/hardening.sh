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
# The words of an exit_table line, its placeholders filled in.
words() {
  local line=$1
  line=${line//ROBOT/$R} line=${line//POSES/$POSES} line=${line//MEM//proc/self/mem} line=${line//DATA/$data}
  # shellcheck disable=SC2086
  echo ${line//IMAGE/$data/bad_inputs/image_no_target.png}
}
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
  expect 2 "--poses: must be at most 500 poses, got 100000" demo --poses 100000 --out demo
  expect 2 "--holdout: must be at most 500 poses, got 100000" demo --holdout 100000 --out demo
  expect 2 "--poses: must be at least 8 poses, got -3" demo --poses -3 --out demo
  expect 2 "--focal-error: must be at most 20 percent, got 30" demo --focal-error 30 --out demo
  # Issue 37: a range the step checks too, and the rule no range says, in the flag's name.
  expect 2 "--settle: must be at most 600 s, got 900" acquire --session s --controller sim --camera sim --settle 900
  expect 2 "--holdout-every: must be 0 \(none\) or at least 2, got 1" acquire --session s --controller sim \
    --camera sim --holdout-every 1
  expect 2 "--count: 0 is outside" candidates $R --count 0 --out c.csv
  expect 2 "--count: 'many' is not a whole number" candidates $R --count many --out c.csv
  expect 2 "--candidate-count: must be at least 0" plan $R --candidate-count -5 --out p.csv
  expect 2 "--runs: must be at least 1, got 0" simulate $R --runs 0
  expect 2 "--runs: must be at most 1000000, got 100000000" simulate $R --runs 100000000
  expect 2 "--poses: must be at most 100000 poses, got 1000000" simulate $R --poses 1000000
  expect 2 "--sweep: '8:1e300' is not MIN:MAX" simulate $R --sweep 8:1e300
  expect 2 "--threads: must be at most 256 threads, got 100000" simulate $R --threads 100000
  expect 2 "--threads: -1 is outside \[0, 256\]" render --poses "$POSES" --out r --threads -1
  expect 2 "--threads: 9999 is outside \[0, 256\]" detect --images . --threads 9999
  expect 2 "--threads: 9999 is outside" intrinsics --images . --out cam.yaml --threads 9999
  expect 2 "--threads: 9999 is outside" measure --camera c.yaml --images . --out m.csv --threads 9999
  expect 2 "--min-views: 0 is outside" intrinsics --images . --out cam.yaml --min-views 0
  expect 2 "--dpi: must be at most 1200 dpi, got 1000000" target print --out t.png --dpi 1e6
  expect 0 "--dpi NUMBER:NUMBER in \[50, 1200\]" target print --help  # the range it enforces (issue 36)
  expect 2 "--dpi: must be at least 50 dpi, got 40" target print --out t.png --dpi 40
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
  # A shadow file parses as a mapping whose one key is its first line: that
  # key was echoed whole as the "unknown key" (issue 36).
  printf 'root:$6$SECRETsalt$SECREThash:19000:0:99999:7:::\n' >shadow
  expect 2 "robot file './shadow': the key on line 1: unknown key" robot show ./shadow
  expect 2 "the key on line 1: unknown key" target check --target shadow
  expect 2 "plan settings 'shadow': the key on line 1: unknown key" plan $R --settings shadow --out p.csv
  for args in "robot show ./shadow" "target check --target shadow" "plan $R --settings shadow --out p.csv"; do
    # shellcheck disable=SC2086
    if timeout 20 "$hexcal" $args 2>&1 | grep -q SECRET; then
      echo "FAIL: the error quotes the file: hexcal $args"; failures=$((failures + 1))
    fi
  done
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
  expect 2 "--poses: must be at least 7 poses, got 5" simulate $R --poses 5
  # A folder that cannot be made is bad input everywhere (issue 36: verify
  # gave 1, session init and render 2); a full or read-only disk would be 1.
  : >afile
  expect 2 "afile/s: cannot create the folder: Not a directory" session init afile/s $R \
    --camera sim-4.2mm-1024x768 --target aprilgrid-6x6
  expect 2 "afile/r: cannot create the folder: Not a directory" render --poses "$data/poses/vision_views.csv" \
    --out afile/r
  "$hexcal" demo --poses 8 --holdout 0 --out demo >/dev/null 2>&1 || { echo "FAIL: demo"; failures=$((failures + 1)); }
  expect 2 "afile/x: cannot create the folder: Not a directory" verify --session demo --controller sim --camera sim \
    --poses "$POSES" --keep-images afile/x
  ;;
special_files_everywhere)
  # Issue 36: a FIFO, a device, a folder and a dangling link at every place a
  # file is read. Each gets its own message (core/atomic_file.h
  # OpenFileForReading), exit 2, never a hang. One line a place:
  #   FILE (made, @F@ in ARGS) | kinds it does not apply to | ARGS
  places=$(cat <<'EOF'
r.yaml | | robot check ./@F@
t.yaml | | target check --target @F@
c.yaml | | measure --camera @F@ --images IMAGE --out m.csv
p.yaml | | plan ROBOT --settings @F@ --out p.csv
poses.csv | | ik ROBOT --poses @F@
m.csv | | calibrate ROBOT --measurements @F@ --out cal.yaml
s1/session.yaml | | session status s1
s2/plan.csv | | acquire --session s2 --controller sim --camera sim
s3/legs.csv | | calibrate --session s3
img.png | folder | detect --images @F@
img.png | folder | measure --camera sim-4.2mm-1024x768 --images @F@ --out m.csv
from.png | | session record s4 --image a.png LEGS --from @F@
s5/images/a.png | | session record s5 --image a.png LEGS
v.png | | acquire --session s6 --controller sim --camera file:@F@
EOF
)
  for kind in fifo device folder dangling; do
    case $kind in
      fifo) message="not a regular file \(a FIFO\)" ;;
      device) message="not a regular file \(a character device\)" ;;
      folder) message="is a directory, not a file" ;;
      dangling) message="a symbolic link to a missing file" ;;
    esac
    while IFS='|' read -r name skip args; do
      name=$(echo $name)
      case " $skip " in *" $kind "*) continue ;; esac
      mkdir "$kind" && cd "$kind" || exit 1
      for s in s1 s2 s3 s4 s5 s6; do
        case "$args" in *" $s"*) ;; *) continue ;; esac
        "$hexcal" session init $s $R --camera sim-4.2mm-1024x768 --target aprilgrid-6x6 >/dev/null || exit 1
      done
      [ -d s6 ] && cp "$POSES" s6/plan.csv
      rm -f "$name"
      mkdir -p "$(dirname "$name")"
      case $kind in
        fifo) mkfifo "$name" ;;
        device) ln -s /dev/zero "$name" ;;
        folder) mkdir "$name" ;;
        dangling) ln -s "$work/gone" "$name" ;;
      esac
      args=${args//@F@/$name} args=${args//ROBOT/$R} args=${args//LEGS/--legs 1,1,1,1,1,1}
      # shellcheck disable=SC2086
      expect 2 "$(basename "$name").*$message" ${args//IMAGE/$data/bad_inputs/image_garbage.png}
      cd "$work" && rm -rf "$kind"
    done <<<"$places"
  done
  ;;
exit_table)
  # Issue 36: one table of exit codes for every command (docs/cli.md), each
  # error after "hexcal COMMAND: ", CLI11's own refusals too; every command
  # takes --json but sim-camera (a server until Ctrl-C; README.md says so).
  # Issue 37: one code per tier, the same fault the same code everywhere.
  # One line a command: COMMAND | a bad input (exit 2) | an I/O fault (exit 4)
  # | a failed computation (exit 1), where the command computes something
  # that can fail from valid input. The I/O faults: a file that opens but
  # whose read fails (/proc/self/mem: EIO at address 0), named directly or as
  # a session's session.yaml and results/manifest.json (session io); an
  # output under /sys (EACCES or EPERM, for root too).
  "$hexcal" session init s $R --camera sim-4.2mm-1024x768 --target aprilgrid-6x6 >/dev/null || exit 1
  mkdir -p io/results && ln -s /proc/self/mem io/session.yaml && ln -s /proc/self/mem io/results/manifest.json
  printf 'x,y,z,q1,q2,q3,L1,L2,L3,L4,L5,L6\n0,0,45,0,0,0,3.4,0,3.4,0,3.4,0\n' >far.csv
  commands=$(cat <<'EOF'
robot check | robot check ./missing.yaml | robot check MEM |
robot show | robot show ./missing.yaml | robot show MEM |
ik | ik --robot missing.yaml --poses POSES | ik ROBOT --poses POSES --out /sys/ik.csv |
fk | fk ROBOT --legs 1,2 | fk --robot MEM --legs 1,1,1,1,1,1 | fk ROBOT --legs 3.5,0,3.5,0,3.5,0 --start 0,0,60,0,0,0
candidates | candidates ROBOT --count 0 --out c.csv | candidates ROBOT --count 5 --out /sys/c.csv |
indices | indices ROBOT --poses missing.csv | indices ROBOT --poses MEM |
demo | demo --poses 5 --out d | demo --poses 8 --out /sys/d |
plan | plan ROBOT --poses 6 --out p.csv | plan ROBOT --settings MEM --out p.csv |
calibrate | calibrate ROBOT --measurements missing.csv --out cal.yaml | calibrate ROBOT --measurements MEM --out cal.yaml | calibrate ROBOT --measurements DATA/bad_inputs/measurements_singular_poses.csv --out cal.yaml
validate | validate ROBOT --measurements missing.csv | validate ROBOT --measurements MEM | validate ROBOT --measurements far.csv
simulate | simulate ROBOT --runs 0 | simulate --robot MEM --runs 1 |
study | study --session missing | study --session io |
target check | target check --target missing.yaml | target check --target MEM |
target print | target print --target missing.yaml --out t.pdf | target print --target aprilgrid-6x6 --out /sys/t.pdf |
detect | detect --images missing | detect --target MEM --images IMAGE |
render | render --camera missing.yaml --poses POSES --out r | render --poses POSES --out /sys/r |
intrinsics | intrinsics --images missing --out cam.yaml | intrinsics --target MEM --images IMAGE --out cam.yaml |
measure | measure --camera missing.yaml --images missing --out m.csv | measure --camera MEM --images IMAGE --out m.csv |
session init | session init s2 --robot missing.yaml --camera sim-4.2mm-1024x768 --target aprilgrid-6x6 | session init /sys/s2 ROBOT --camera sim-4.2mm-1024x768 --target aprilgrid-6x6 |
session status | session status missing | session status io |
session record | session record s --image a.png --legs 0x10,1,1,1,1,1 | session record io --image a.png --legs 1,1,1,1,1,1 |
report | report --session missing --out r.html | report --session io --out r.html |
acquire | acquire --session missing --controller sim --camera sim | acquire --session io --poses POSES --controller sim --camera sim |
verify | verify --session missing --controller sim --camera sim --poses POSES | verify --session io --controller sim --camera sim --poses POSES |
sim-camera | sim-camera --session missing --machine-robot missing.yaml | sim-camera --session io --machine-robot MEM |
export | export --robot missing.yaml --out x.hal | export --robot MEM --out x.hal |
camera show | camera show missing.yaml | camera show MEM |
camera convert | camera convert missing.yaml --to ros --out x.yaml | camera convert sim-4.2mm-1024x768 --to ros --out /sys/x.yaml |
EOF
)
  while IFS='|' read -r command bad io failed; do
    command=$(echo $command)
    # shellcheck disable=SC2046
    expect 2 "^hexcal $command: " $(words "$bad")
    # shellcheck disable=SC2086
    expect 2 "^hexcal $command: " $command --no-such-option
    # shellcheck disable=SC2046
    expect 4 "^hexcal $command: .*(Input/output error|Permission denied|Operation not permitted)" $(words "$io")
    # shellcheck disable=SC2046
    [ -n "$(words "$failed")" ] && expect 1 "^hexcal $command: " $(words "$failed")
    # shellcheck disable=SC2086
    if [ "$command" != sim-camera ] && ! "$hexcal" $command --help | grep -q -- "--json"; then
      echo "FAIL: hexcal $command takes no --json"; failures=$((failures + 1))
    fi
  done <<<"$commands"
  # A video device that is not there is an I/O fault too: the camera's own open failed.
  expect 4 "^hexcal acquire: v4l2:97: cannot open /dev/video97" acquire --session s --poses "$POSES" \
    --controller sim --camera v4l2:97
  leftovers=$(ls -A | grep -v -x -e s -e io -e far.csv)
  [ -n "$leftovers" ] && { echo "FAIL: files left behind: $leftovers"; failures=$((failures + 1)); }
  ;;
text_and_numbers)
  # Issue 36: JSON output never throws on invalid UTF-8 (it is replaced by
  # U+FFFD, as in the session's manifest); a control character in an image
  # name is refused, legs.csv cannot hold it; numbers are decimal and exact.
  latin1=$(printf 't\351.png')
  output=$(timeout 20 "$hexcal" target print --out "$latin1" --json 2>&1)
  rc=$?
  if [ "$rc" -ne 0 ] || ! python3 -c 'import json,sys; o=json.loads(sys.stdin.read()); assert o["out"] == "t\ufffd.png", o["out"]' <<<"$output"; then
    echo "FAIL: exit $rc, not one JSON object with out t\ufffd.png: $output"; failures=$((failures + 1))
  else
    echo "ok: hexcal target print --out t\\351.png --json"
  fi
  # An escape sequence in a robot's name is shown escaped, never sent raw.
  "$hexcal" export $R --format robot --out red.yaml >/dev/null || exit 1
  sed -i 's/^name: .*/name: "bad\\e[31mred"/' red.yaml
  expect 0 "ok: robot 'bad\\\\x1b\[31mred' is valid" robot check ./red.yaml
  if timeout 20 "$hexcal" robot show ./red.yaml 2>&1 | grep -q "$(printf '\033')"; then
    echo "FAIL: robot show sends the escape sequence raw"; failures=$((failures + 1))
  fi
  "$hexcal" session init s $R --camera sim-4.2mm-1024x768 --target aprilgrid-6x6 >/dev/null || exit 1
  IMG=$data/bad_inputs/image_no_target.png
  expect 2 "a control character in an image name; legs.csv cannot hold it" session record s --image "$(printf 'a\nb.png')" \
    --legs 1,1,1,1,1,1 --from "$IMG"
  expect 2 "'a\\\\x1b\[2Jb.png': a control character" session record s --image "$(printf 'a\033[2Jb.png')" \
    --legs 1,1,1,1,1,1 --from "$IMG"
  [ -e s/legs.csv ] && { echo "FAIL: legs.csv written"; failures=$((failures + 1)); }
  [ -n "$(ls -A s/images)" ] && { echo "FAIL: an image was copied: $(ls -A s/images)"; failures=$((failures + 1)); }
  # session.yaml with a key twice: the first was read, the second ignored.
  cp -r s dup && cp "$data/../../fuzz/seeds/session_duplicate_key.yaml" dup/session.yaml
  expect 2 "dup/session.yaml: frames.base_from_camera: duplicate key \(lines 6 and 7\)" session status dup
  expect 2 "--legs: '0x10' is not a finite number" session record s --image a.png --legs 0x10,1,1,1,1,1 --from "$IMG"
  # Readings more than a stroke length outside the robot file's strokes
  # (INRIA: [0, 3.5] cm, so [-3.5, 7] cm) are refused with the reading, its
  # value and the range (they were recorded "done"); mm on a cm robot is named.
  expect 2 "--legs: L1 = 1e\+300 cm is outside \[-3.5, 7\] cm, leg 1's stroke \[0, 3.5\] cm give or take" \
    session record s --image a.png --legs 1e300,1,1,1,1,1 --from "$IMG"
  expect 2 "--legs: L1 = -1000 cm is outside \[-3.5, 7\] cm" session record s --image a.png \
    --legs -1000,1,1,1,1,1 --from "$IMG"
  expect 2 "--legs: L6 = 7.2 cm is outside \[-3.5, 7\] cm, leg 6's stroke" session record s --image a.png \
    --legs 1,1,1,1,1,7.2 --from "$IMG"
  expect 2 "--legs: readings look like mm, the robot 'inria-left-hand' is in cm: L1 = 22.1" session record s \
    --image a.png --legs 22.1,22.4,21.9,22.0,22.3,22.2 --from "$IMG"
  expect 2 "--seed: must be at most 9007199254740992, got 9007199254740993" study --session s --seed 9007199254740993
  expect 2 "--seed: '0x10' is not a whole number in decimal digits" candidates $R --count 5 --seed 0x10 --out c.csv
  expect 2 "--seed: '010': a leading 0" candidates $R --count 5 --seed 010 --out c.csv
  expect 2 "--seed: -1 is negative" acquire --session s --controller sim --camera sim --seed -1
  expect 2 "--seed: 18446744073709551616 is outside \[0, 18446744073709551615\]" acquire --session s \
    --controller sim --camera sim --seed 18446744073709551616
  expect 2 "--settle: expected a finite number, got '0x1p3'" acquire --session s --controller sim --camera sim \
    --settle 0x1p3
  [ -e s/legs.csv ] && { echo "FAIL: legs.csv written"; failures=$((failures + 1)); }
  [ -e c.csv ] && { echo "FAIL: c.csv written"; failures=$((failures + 1)); }
  ;;
session_paths)
  # Issue 36: session init keeps a file's path relative to the session folder,
  # so the session works from any directory (it kept the path as typed).
  mkdir -p here/runs && "$hexcal" export $R --format robot --out here/robot.yaml >/dev/null || exit 1
  (cd here && "$hexcal" session init runs/s --robot robot.yaml --camera sim-4.2mm-1024x768 \
    --target aprilgrid-6x6 >/dev/null) || { echo "FAIL: session init"; failures=$((failures + 1)); }
  grep -qx "robot: ../../robot.yaml" here/runs/s/session.yaml || {
    echo "FAIL: session.yaml: $(grep robot: here/runs/s/session.yaml)"; failures=$((failures + 1)); }
  expect 0 "robot +done" session status here/runs/s
  ;;
*)
  echo "unknown case $case"; exit 2
  ;;
esac
[ "$failures" -eq 0 ] || { echo "$failures failure(s)"; exit 1; }
