#!/usr/bin/env bash
# session.sh HEXCAL DATA: a session folder end to end on a virtual robot and
# camera. A true robot (the preset with every parameter moved by up to 0.05 cm),
# a camera 50 cm above the platform, images rendered at 16 poses, readings from
# the true robot's IK; `calibrate --session` must cut the held-out pose error at
# least 3 times, leave images/ and legs.csv untouched and reuse
# camera_poses.csv; `report` writes one HTML page with its charts. Bad folders get errors naming the file and line.
set -eu
hexcal=$1 data=$2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
"$hexcal" candidates --robot inria-left-hand --kind random --count 16 --seed 5 --out "$dir/poses.csv" >/dev/null
CLI_DIR=$(dirname "$0") python3 - "$dir" "$data/../../resources/robots/inria-left-hand.yaml" <<'PY'
import csv, math, os, random, re, sys
sys.dont_write_bytecode = True  # nothing written into the source tree
sys.path.insert(0, os.environ["CLI_DIR"])
from rigid import comp, inv, pose, vec
d, preset = sys.argv[1], sys.argv[2]
random.seed(7)
base_from_camera = pose([1.5, -2.0, 103.0, 180.0, 2.0, -4.0])  # cm, degrees
platform_from_target = pose([-11.25, -11.25, 0.5, 0.0, 0.0, 5.0])
def moved(m):
    return '[' + ', '.join('%.5f' % (float(x) + random.uniform(-0.05, 0.05)) for x in m.group(2).split(',')) + ']'
truth = re.sub(r'(a|b): \[([^\]]*)\]', lambda m: m.group(1) + ': ' + moved(m), open(preset).read())
open(d + '/truth.yaml', 'w').write(truth)
with open(d + '/camera_poses.csv', 'w') as out:
    out.write('x,y,z,q1,q2,q3\n')
    for row in csv.DictReader(l for l in open(d + '/poses.csv') if not l.startswith('#')):
        base_from_platform = pose([float(row[k]) for k in ('x', 'y', 'z', 'q1', 'q2', 'q3')])
        v = vec(comp(comp(inv(base_from_camera), base_from_platform), platform_from_target))
        out.write(','.join('%.9f' % x for x in [10 * x for x in v[:3]] + v[3:]) + '\n')  # mm
PY
"$hexcal" ik --robot "$dir/truth.yaml" --poses "$dir/poses.csv" --out "$dir/ik.csv" >/dev/null
"$hexcal" render --camera sim-4.2mm-1024x768 --poses "$dir/camera_poses.csv" --out "$dir/render" --seed 2 >/dev/null

s=$dir/s
"$hexcal" session init --robot inria-left-hand --camera sim-4.2mm-1024x768 --target aprilgrid-6x6 \
  --noise-position 0.005 --noise-angle 0.02 --noise-leg 0.001 "$s" >/dev/null
if "$hexcal" session init --robot inria-left-hand --camera sim-4.2mm-1024x768 --target aprilgrid-6x6 "$s" \
  2>"$dir/err"; then exit 1; fi
grep -q "session.yaml: exists" "$dir/err"
cp "$dir"/render/view_*.png "$s/images/"
# image,L1..L6,holdout from the IK table; every fourth image held out.
awk -F, 'NR > 1 { printf "view_%04d.png,%s,%s,%s,%s,%s,%s,%d\n", NR - 2, $7, $8, $9, $10, $11, $12, (NR - 2) % 4 == 3 }' \
  "$dir/ik.csv" | sed '1i image,L1,L2,L3,L4,L5,L6,holdout' >"$s/legs.csv"
before=$(cat "$s/legs.csv" "$s"/images/* | cksum)

"$hexcal" calibrate --session "$s" --json >"$dir/report.json"
python3 - "$dir/report.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
assert r["calibration_images"] == 12 and r["held_out_images"] == 4, r
before, after = r["validation"]["before"], r["validation"]["after"]
assert after["position_rms"] * 3 < before["position_rms"], (before, after)
assert after["orientation_rms"] * 3 < before["orientation_rms"], (before, after)
assert r["registration"]["position_rms"] < 0.5 and r["closure_after_calibration"]["position_rms"] < 0.02, r
PY
[ "$(cat "$s/legs.csv" "$s"/images/* | cksum)" = "$before" ]
[ -s "$s/results/calibrated.yaml" ] && [ -s "$s/results/report.json" ] && grep -q "base_from_camera:" "$s/session.yaml"
"$hexcal" robot check "$s/results/calibrated.yaml" >/dev/null
"$hexcal" report --session "$s" --out "$dir/report.html" | grep -q "written to"
# 3 charts, and the 3 of the per-corner diagnostics (results/corner_residuals.csv).
[ "$(grep -c '<svg' "$dir/report.html")" -eq 6 ] && grep -q "Held-out validation" "$dir/report.html"
grep -q "<h2>Per-corner diagnostics" "$dir/report.html"
if "$hexcal" report --session "$s" --out "$dir/report.html" 2>"$dir/err"; then exit 1; fi
grep -q "report.html: exists; use --force" "$dir/err"
# Measured images are not measured again.
cp "$s/camera_poses.csv" "$dir/m1.csv"
"$hexcal" calibrate --session "$s" --json >"$dir/report2.json"
cmp "$s/camera_poses.csv" "$dir/m1.csv"
# ... and give the same calibration: the pose covariance read back whole.
python3 - "$dir/report.json" "$dir/report2.json" <<'PY'
import json, sys
a, b = (json.load(open(f)) for f in sys.argv[1:3])
for p, q in zip(a["parameters"], b["parameters"]):
    # Equal up to the solvers' tolerances: far below σ (a lost correlation moved them by σ/2).
    assert abs(p["estimate"] - q["estimate"]) < 1e-4 * p["sigma"] and abs(p["sigma"] - q["sigma"]) < 1e-4 * p["sigma"], (p, q)
PY

# A session whose results/ was deleted calibrates again: results/ is recreated (issue 13).
rm -rf "$s/results"
"$hexcal" calibrate --session "$s" >/dev/null
[ -s "$s/results/calibrated.yaml" ] && [ -s "$s/results/report.json" ]

# Bad folders: a row for an absent image, an image without a row, a short row.
cp "$s/legs.csv" "$dir/legs.good"
echo "view_0099.png,1,1,1,1,1,1,0" >>"$s/legs.csv"
if "$hexcal" calibrate --session "$s" 2>"$dir/err"; then exit 1; else [ $? -eq 2 ]; fi
grep -q "legs.csv:18: image 'view_0099.png' is not in images/" "$dir/err"
grep -v view_0005 "$dir/legs.good" >"$s/legs.csv"
if "$hexcal" calibrate --session "$s" 2>"$dir/err"; then exit 1; fi
grep -q "images/view_0005.png: no row in" "$dir/err"
sed 's/^view_0002.png,\([^,]*\),/view_0002.png,/' "$dir/legs.good" >"$s/legs.csv"
if "$hexcal" calibrate --session "$s" 2>"$dir/err"; then exit 1; fi
grep -q "legs.csv:4: 7 columns, header has 8" "$dir/err"
# Readings in mm for the cm robot: the unit is named, bad input (issue 13).
awk -F, 'BEGIN { OFS = "," } NR == 1 { print; next } { for (i = 2; i <= 7; i++) $i = $i * 10; print }' \
  "$dir/legs.good" >"$s/legs.csv"
if "$hexcal" calibrate --session "$s" 2>"$dir/err"; then exit 1; else [ $? -eq 2 ]; fi
grep -q "legs.csv: readings look like mm, the robot '.*' is in cm: row 1: L" "$dir/err"
