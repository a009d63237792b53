#!/usr/bin/env bash
# acquire.sh HEXCAL: `hexcal acquire` end to end on the sim world
# (docs/acquisition.md). A session on inria-left-hand, a plan of 16 poses in
# the sampling box, acquisition with the sim controller and camera, stopped
# once by Ctrl-C and once by kill -9 and resumed each time without a row
# twice; then `calibrate --session` must beat the nominal robot against the
# hidden truth in SESSION/truth (its 42 parameters in the registered frames,
# at least 2 times closer) and on the held-out poses (3 times). Bad URLs are
# named.
set -eu
hexcal=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
s=$dir/s

"$hexcal" session init --robot inria-left-hand --camera sim-4.2mm-1024x768 --target aprilgrid-6x6 \
  --noise-position 0.005 --noise-angle 0.02 --noise-leg 0.001 "$s" >/dev/null
code=0
"$hexcal" acquire --session "$s" --controller sim --camera sim 2>"$dir/err" || code=$?
[ "$code" -eq 2 ] && grep -q "no plan in the session; run hexcal plan" "$dir/err"
"$hexcal" plan --robot inria-left-hand --poses 16 --candidate-count 400 --seed 3 --no-certificate \
  --candidate-kind random --criterion O1 --tabu 0 --polish 0 \
  --out "$s/plan.csv" >/dev/null

# Bad URLs: bad input (2), naming the URL and what is accepted.
expect_refused() {  # expect_refused PATTERN ARGS...
  local pattern=$1 code=0
  shift
  "$hexcal" acquire --session "$s" "$@" >/dev/null 2>"$dir/err" || code=$?
  [ "$code" -eq 2 ] || { echo "exit $code for $*"; exit 1; }
  grep -q "$pattern" "$dir/err" || { echo "no '$pattern' in: $(cat "$dir/err")"; exit 1; }
}
# aravis: a bad option is refused before any camera is looked for; a build
# without Aravis refuses every aravis: URL, naming the package.
expect_refused "camera 'aravis:Fake_1?exposure=fast': \(exposure 'fast' is not a number\|this hexcal was built without Aravis (install libaravis-dev\)" \
  --controller sim --camera "aravis:Fake_1?exposure=fast"
"$hexcal" target print --target aprilgrid-6x6 --out "$dir/still.png" >/dev/null
expect_refused "controller 'linuxcnc://localhost': no host or no port; expected linuxcnc://HOST:PORT" \
  --controller linuxcnc://localhost --camera "file:$dir/still.png"
expect_refused "file:/no/such.png: /no/such.png: no such file" \
  --controller linuxcnc://localhost:5007 --camera file:/no/such.png
expect_refused "camera 'gige:1': unknown kind 'gige'; accepted forms: sim, v4l2:N, file:PATH" \
  --controller sim --camera gige:1
expect_refused "camera 'sim' renders the sim world's platform: it needs --controller sim" \
  --controller linuxcnc://h:1 --camera sim
# A file where images/ should be is the session's fault (bad input), found before anything moves.
rmdir "$s/images" && echo "not a folder" >"$s/images"
expect_refused "images: cannot write a new file there (nothing was moved): Not a directory" --controller sim --camera sim
[ "$(cat "$s/images")" = "not a folder" ]
[ ! -e "$s/truth" ]
rm "$s/images" && mkdir "$s/images"
[ ! -e "$s/legs.csv" ]
# verify needs the frames a calibration registers.
code=0
"$hexcal" verify --session "$s" --controller sim --camera sim >/dev/null 2>"$dir/err" || code=$?
[ "$code" -eq 2 ] && grep -q "no registered camera and target frames; calibrate it first" "$dir/err"

rows() { if [ -e "$s/legs.csv" ]; then tail -n +2 "$s/legs.csv" | wc -l; else echo 0; fi; }
wait_rows() {  # wait_rows N: until legs.csv has at least N rows (30 s at most)
  for _ in $(seq 300); do [ "$(rows)" -ge "$1" ] && return 0; sleep 0.1; done
  echo "legs.csv never reached $1 rows"; exit 1
}
# Run directly (not through a shell function), so that $! is hexcal's PID.
acquire=("$hexcal" acquire --session "$s" --controller sim --camera sim --holdout-every 4 --seed 2)

# Ctrl-C: the pose being recorded is finished, then exit 1 (cancelled).
"${acquire[@]}" --settle 0.2 >/dev/null 2>"$dir/err1" &
pid=$!
wait_rows 3
kill -INT $pid
code=0
wait $pid || code=$?
[ "$code" -eq 1 ] && grep -q "hexcal acquire: cancelled" "$dir/err1"
after_cancel=$(rows)
[ "$after_cancel" -ge 3 ] && [ "$after_cancel" -lt 16 ]

# kill -9 in the middle of a later pose; then the rest.
"${acquire[@]}" --settle 0.2 >/dev/null 2>"$dir/err2" &
pid=$!
wait_rows $((after_cancel + 3))
kill -9 $pid
wait $pid 2>/dev/null || true
after_kill=$(rows)
"${acquire[@]}" --json >"$dir/acquire.json" 2>"$dir/err3"
python3 - "$dir/acquire.json" "$after_kill" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
assert r["recorded"] + r["already_recorded"] == 16 and r["failed"] == 0, r
assert r["already_recorded"] == int(sys.argv[2]), (r["already_recorded"], sys.argv[2])
assert [p["image"] for p in r["poses"]] == ["pose_%04d.png" % k for k in range(16)]
assert all(p["holdout"] == (p["index"] % 4 == 3) for p in r["poses"] if p["state"] == "recorded")
PY
[ "$(rows)" -eq 16 ] && [ "$(ls "$s/images" | wc -l)" -eq 16 ]
[ "$(cut -d, -f1 "$s/legs.csv" | sort | uniq -d | wc -l)" -eq 0 ]
grep -q "sim controller (inria-left-hand" "$dir/acquire.json"

# Nothing left to do: a run records nothing and says so.
"${acquire[@]}" >"$dir/again" 2>/dev/null
grep -q "0 recorded, 16 already recorded, 0 failed, of 16 poses" "$dir/again"
# Another seed would be another hidden robot: refused.
expect_refused "drawn with another --seed than 5" --controller sim --camera sim --seed 5

# The calibration from the acquired session against the hidden truth.
"$hexcal" calibrate --session "$s" --json >"$dir/report.json" 2>"$dir/err4"
# The calibration against the truth and on the held-out poses (truth_error.py).
python3 "$(dirname "$0")/truth_error.py" "$s" "$(dirname "$0")/../../resources/robots/inria-left-hand.yaml" \
  "$dir/report.json"

# verify through the sim camera: the sim controller keeps the nominal robot,
# so the commanded poses are off by the nominal robot's error (about 0.09 cm
# on the held-out poses above), and every pose is seen.
head -n 5 "$s/plan.csv" >"$dir/check.csv"
"$hexcal" verify --session "$s" --controller sim --camera sim --seed 2 --poses "$dir/check.csv" --settle 0 \
  --json >"$dir/verify.json" 2>"$dir/err5"
python3 - "$dir/verify.json" <<'PY'
import json, sys
v = json.load(open(sys.argv[1]))
assert v["seen"] == 4 and v["failed"] == 0, v
assert 0.02 < v["position_rms"] < 0.3, v["position_rms"]
assert all(len(p["seen"]) == 6 and p["reprojection_rms_px"] < 0.5 for p in v["poses"]), v["poses"]
print("verify on the sim: position RMS %.4f cm, orientation RMS %.4f deg" % (v["position_rms"], v["orientation_rms"]))
PY
# A camera that is not there: hexcal's message, not OpenCV's log lines
# (they come through with `hexcal --verbose`).
"$hexcal" acquire --session "$s" --controller sim --camera v4l2:97 >/dev/null 2>"$dir/quiet" || true
grep -q "v4l2:97: cannot open /dev/video97" "$dir/quiet" && ! grep -q "WARN" "$dir/quiet" || { cat "$dir/quiet"; exit 1; }
"$hexcal" --verbose acquire --session "$s" --controller sim --camera v4l2:97 >/dev/null 2>"$dir/loud" || true
grep -q "WARN.*cap_v4l" "$dir/loud" || { cat "$dir/loud"; exit 1; }
# A corrupt video: hexcal's one line, not FFmpeg's ("[matroska,webm @ 0x...]
# EBML header parsing failed"), which --verbose lets through (issue 36).
video=$(dirname "$0")/../data/bad_inputs/video_corrupt.mkv
code=0
"$hexcal" acquire --session "$s" --controller sim --camera "file:$video" >/dev/null 2>"$dir/quiet" || code=$?
[ "$code" -eq 2 ] && [ "$(wc -l <"$dir/quiet")" -eq 1 ] && grep -q "^hexcal acquire: .*not a video" "$dir/quiet" ||
  { cat "$dir/quiet"; exit 1; }
"$hexcal" --verbose acquire --session "$s" --controller sim --camera "file:$video" >/dev/null 2>"$dir/loud" || true
grep -q "matroska.*EBML header parsing failed" "$dir/loud" || { cat "$dir/loud"; exit 1; }
echo "acquire: ok"
