#!/usr/bin/env bash
# diagnosis.sh HEXCAL: diagnostics that name the cause (issue 34; docs/
# calibration.md, "Closure by image"). On the default demo session (24
# calibration images):
# - a swapped image (view_0005 replaced by a copy of view_0003): named with
#   its legs.csv line as a swapped or mislabelled image, left out of the
#   registration, the fit and the closure; the verdict on the rest is good
#   (before: closure 8.53 cm, "poor", "recalibrate the camera");
# - the camera file's fx and fy 5 % too large: the calibration from pixels
#   finds them, and the verdict names the focal length and the camera, not
#   the robot file; with the fitted camera (results/camera.yaml) the verdict
#   is good again.
set -eu
hexcal=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
"$hexcal" demo --out "$dir/demo" >/dev/null 2>&1

cp -r "$dir/demo" "$dir/swap"
cp "$dir/swap/images/view_0003.png" "$dir/swap/images/view_0005.png"
line=$(grep -n "^view_0005.png," "$dir/swap/legs.csv" | cut -d: -f1)
"$hexcal" calibrate --session "$dir/swap" >"$dir/swap.txt" 2>&1 || { cat "$dir/swap.txt"; exit 1; }
grep -q "^left out: view_0005.png (legs.csv line $line), closure .*: its board pose disagrees with [4-6] of 6 legs: a swapped or mislabelled image?" "$dir/swap.txt" ||
  { cat "$dir/swap.txt"; exit 1; }
grep -q "^Verdict: good$" "$dir/swap.txt" || { cat "$dir/swap.txt"; exit 1; }
grep -q "^  good       outliers: 1 calibration image of 24 left out for [0-9]* flagged readings: view_0005.png (legs.csv line $line), a swapped or mislabelled image?" "$dir/swap.txt"
grep -q "^  good       closure: " "$dir/swap.txt"
if grep -q "recalibrate the camera" "$dir/swap.txt"; then echo "a swapped image blamed on the camera"; exit 1; fi

cp -r "$dir/demo" "$dir/focal"
"$hexcal" camera convert sim-4.2mm-1024x768 --to opencv --out "$dir/focal/camera.yaml" >/dev/null
sed -i 's/data: \[ 903.2, 0, 515.3, 0, 903.2/data: [ 948.36, 0, 515.3, 0, 948.36/' "$dir/focal/camera.yaml"
sed -i 's/^camera: .*/camera: camera.yaml/' "$dir/focal/session.yaml"
"$hexcal" calibrate --session "$dir/focal" >"$dir/focal.txt" 2>&1 || { cat "$dir/focal.txt"; exit 1; }
grep -q "^  acceptable camera (scale): largest change 4.7[0-9] % (f[xy] 948 -> 903 " "$dir/focal.txt" ||
  { cat "$dir/focal.txt"; exit 1; }
grep "^  poor       parameters (change)" "$dir/focal.txt" | grep -q "; recalibrate the camera (hexcal intrinsics)" ||
  { cat "$dir/focal.txt"; exit 1; }
cp "$dir/focal/results/camera.yaml" "$dir/focal/fitted.yaml"
sed -i 's/^camera: .*/camera: fitted.yaml/' "$dir/focal/session.yaml"
"$hexcal" calibrate --session "$dir/focal" >"$dir/fitted.txt" 2>&1 || { cat "$dir/fitted.txt"; exit 1; }
grep -q "^Verdict: good$" "$dir/fitted.txt" || { cat "$dir/fitted.txt"; exit 1; }
echo "diagnosis: ok"
