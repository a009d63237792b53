#!/usr/bin/env bash
# vision_intrinsics.sh HEXCAL DATA: `hexcal intrinsics` on ten rendered views
# recovers the simulated camera and writes a camera file that `measure` reads;
# the same through a fisheye camera file with --model pinhole-equi; too few
# views, mixed image sizes and an unknown --model are clear errors (exit 2).
set -eu
hexcal=$1 data=$2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
"$hexcal" render --camera sim-4.2mm-1024x768 --poses "$data/poses/vision_views.csv" --out "$dir/views" >/dev/null
"$hexcal" intrinsics --images "$dir/views" --out "$dir/camera.yaml" --json >"$dir/out.json"
grep -q '"used_views": 10' "$dir/out.json"
[ -s "$dir/camera.coverage.png" ] && [ -s "$dir/camera.residuals.png" ]
# The per-corner diagnostics (docs/calibration.md): the 10 worst corners named,
# the largest first, the histogram's counts and the coverage grid's hold every corner.
python3 - "$dir/out.json" <<'PY'
import json, sys
c = json.load(open(sys.argv[1]))["corners"]
worst = [w["residual_px"] for w in c["worst"]]
assert len(worst) == 10 and worst == sorted(worst, reverse=True), worst
assert all(w["image"].endswith(".png") and 0 <= w["corner"] <= 3 for w in c["worst"]), c["worst"]
h = c["histogram"]
assert sum(h["counts"]) + h["beyond"] == c["corners"] == sum(c["coverage"]["counts"]), c
assert c["sigma_px"] > 0 and c["rms_px"] < 0.2, c
PY
"$hexcal" intrinsics --images "$dir/views" --out "$dir/again.yaml" | grep -A1 "worst corners (residual = projected - detected):" |
  grep -q "  .*views/.*\.png tag [0-9]* corner [0-3] at (.*): .* px (.* sigma)"
head -1 "$dir/camera.yaml" | grep -q '%YAML:1.0'
# fx within 2 px of 903.2
fx=$(grep -A4 '^camera_matrix' "$dir/camera.yaml" | sed -n 's/.*data: \[ \([0-9.]*\),.*/\1/p')
awk -v fx="$fx" 'BEGIN { d = fx - 903.2; if (d < 0) d = -d; exit !(d < 2) }'
"$hexcal" measure --camera "$dir/camera.yaml" --images "$dir/views" --out "$dir/m.csv" | grep -q "10 images: 10 ok"

# A board described with the wrong spacing: calibrateCamera still returns a
# camera; hexcal refuses it with the diagnosis and writes nothing (exit 2).
sed -e 's/^tag_spacing: .*/tag_spacing: 0.5/' "$data/../../resources/targets/aprilgrid-6x6.yaml" >"$dir/wrong.yaml"
code=0
"$hexcal" intrinsics --images "$dir/views" --target "$dir/wrong.yaml" --out "$dir/wrong_cam.yaml" 2>"$dir/err" || code=$?
[ "$code" -eq 2 ]
grep -q "is over the 1 px limit (--max-rms); the camera file was not written" "$dir/err"
grep -q "a systematic error, not a bad image" "$dir/err"
grep -q "spacing 0.5" "$dir/err"
[ ! -e "$dir/wrong_cam.yaml" ]
# The same wrong target in measure: every image fits badly, and it says why.
code=0
"$hexcal" measure --camera "$dir/camera.yaml" --target "$dir/wrong.yaml" --images "$dir/views" --out "$dir/w.csv" \
  >/dev/null 2>"$dir/err" || code=$?
[ "$code" -eq 1 ]
grep -q "no image gave a pose: 10 of 10 images that show the board fit it badly" "$dir/err"
# The fisheye: rendered through an equidistant camera file, calibrated with --model pinhole-equi.
cat >"$dir/fisheye.yaml" <<'END'
%YAML:1.0
---
image_width: 1024
image_height: 768
distortion_model: equidistant
camera_matrix: !!opencv-matrix
   rows: 3
   cols: 3
   dt: d
   data: [ 520.4, 0, 515.3, 0, 519.8, 380.1, 0, 0, 1 ]
distortion_coefficients: !!opencv-matrix
   rows: 4
   cols: 1
   dt: d
   data: [ 0.05, -0.02, 0.004, -0.0005 ]
END
"$hexcal" render --camera "$dir/fisheye.yaml" --poses "$data/poses/vision_views.csv" --out "$dir/fisheye" >/dev/null
"$hexcal" intrinsics --model pinhole-equi --images "$dir/fisheye" --out "$dir/fisheye_out.yaml" --json >"$dir/fisheye.json"
grep -q '"model": "pinhole-equi"' "$dir/fisheye.json"
# Two of the views (0.56 m, tilted 44 deg) leave bit cells under 3 px at f = 520 px; the
# segmentation of the image as it is finds them (docs/vision.md, "Detection"): all 10 used.
grep -q '"used_views": 10' "$dir/fisheye.json"
grep -q '^distortion_model: equidistant' "$dir/fisheye_out.yaml"
# fx within 0.5 % of 520.4
fx=$(grep -A4 '^camera_matrix' "$dir/fisheye_out.yaml" | sed -n 's/.*data: \[ \([0-9.]*\),.*/\1/p')
awk -v fx="$fx" 'BEGIN { d = fx - 520.4; if (d < 0) d = -d; exit !(d < 2.6) }'
"$hexcal" measure --camera "$dir/fisheye_out.yaml" --images "$dir/fisheye" --out "$dir/fm.csv" | grep -q "10 images: 10 ok"
code=0
"$hexcal" intrinsics --model omni --images "$dir/fisheye" --out "$dir/never.yaml" 2>"$dir/err" || code=$?
[ "$code" -eq 2 ]
grep -q "model" "$dir/err"

mkdir "$dir/few"
cp "$dir/views/view_0000.png" "$dir/views/view_0001.png" "$dir/few/"
code=0
"$hexcal" intrinsics --images "$dir/few" --out "$dir/few.yaml" 2>"$dir/err" || code=$?
[ "$code" -eq 1 ]  # too few usable views: a failed computation, like too few feasible poses
grep -q "too few usable views: 2 of 2 images" "$dir/err"
# Images, none of which shows the target: bad input (exit 2; issue 36), as
# measure and calibrate --session have it.
mkdir "$dir/blank"
cp "$data/bad_inputs/image_no_target.png" "$dir/blank/grey.png"
code=0
"$hexcal" intrinsics --images "$dir/blank" --out "$dir/blank.yaml" 2>"$dir/err" || code=$?
[ "$code" -eq 2 ] || { cat "$dir/err"; exit 1; }
grep -q "no image shows the target: 0 of 1 images show at least 4 target tags (.*blank/grey.png: 0 tags)" "$dir/err"
"$hexcal" target print --out "$dir/few/print.png" --dpi 50 >/dev/null
code=0
"$hexcal" intrinsics --images "$dir/few" --out "$dir/few.yaml" 2>"$dir/err" || code=$?
[ "$code" -eq 2 ]
grep -q "images have different sizes" "$dir/err"
echo "ok: vision intrinsics"
