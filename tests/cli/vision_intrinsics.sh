#!/usr/bin/env bash
# vision_intrinsics.sh HEXCAL DATA: `hexcal intrinsics` on ten rendered views
# recovers the simulated camera and writes a camera file that `measure` reads;
# too few views and mixed image sizes are clear errors (exit 2).
set -eu
hexcal=$1 data=$2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
"$hexcal" render --camera sim-4.2mm-1024x768 --poses "$data/poses/vision_views.csv" --out "$dir/views" >/dev/null
"$hexcal" intrinsics --images "$dir/views" --out "$dir/camera.yaml" --json >"$dir/out.json"
grep -q '"used_views": 10' "$dir/out.json"
[ -s "$dir/camera.coverage.png" ]
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

mkdir "$dir/few"
cp "$dir/views/view_0000.png" "$dir/views/view_0001.png" "$dir/few/"
code=0
"$hexcal" intrinsics --images "$dir/few" --out "$dir/few.yaml" 2>"$dir/err" || code=$?
[ "$code" -eq 1 ]  # too few usable views: a failed computation, like too few feasible poses
grep -q "too few usable views: 2 of 2 images" "$dir/err"
"$hexcal" target print --out "$dir/few/print.png" --dpi 50 >/dev/null
code=0
"$hexcal" intrinsics --images "$dir/few" --out "$dir/few.yaml" 2>"$dir/err" || code=$?
[ "$code" -eq 2 ]
grep -q "images have different sizes" "$dir/err"
echo "ok: vision intrinsics"
