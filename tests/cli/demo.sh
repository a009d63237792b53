#!/usr/bin/env bash
# demo.sh HEXCAL: `hexcal demo` end to end on a small case (docs/session.md):
# plan 14 poses, render, measure, register, calibrate, validate on 4 held-out
# images. The calibrated parameters must be within their 3σ of the hidden
# truth for ≥ 95 % of them and much closer than the nominal ones, the held-out
# pose error must drop at least 3 times, and report.html must hold its charts.
# A second run into the folder needs --force; a folder that is not a demo is
# never replaced.
set -eu
hexcal=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT

for robot in inria-left-hand deltalab-table; do
  out=$dir/$robot
  "$hexcal" demo --robot "$robot" --poses 14 --holdout 4 --seed 3 --out "$out" --json >"$dir/summary.json" 2>"$dir/log"
  grep -q "\[5/5" "$dir/log"  # progress of every step
  # The virtual camera has no bias (docs/calibration.md, "Bias along the optical axis").
  grep -q "camera-frame residuals (.*, 14 images, .*): no bias along the optical axis" "$dir/log"
  unit=$([ "$robot" = inria-left-hand ] && echo cm || echo mm)
  # One length unit per line (issue 39: "±0.5 mm" stood beside "±0.001 cm").
  if grep -E '\bmm\b' "$dir/log" | grep -Eq '\bcm\b'; then grep -E '\bmm\b' "$dir/log" | grep -E '\bcm\b'; exit 1; fi
  # O1 and O2 with their unit and meaning, on the plan's line and in the report (issue 39).
  grep -q "candidates; O1 [0-9.]* -> [0-9.]* $unit, O2 [0-9.e-]* -> [0-9.e-]* (random set -> plan) .*O1 the volume of the parameters' uncertainty, in $unit; O2 sigma_min / sigma_max, a ratio" "$dir/log"
  python3 - "$dir/summary.json" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
assert s["within_3sigma"] >= 0.95, s["within_3sigma"]
e = s["parameter_error"]
assert e["mean"] * 5 < e["nominal_mean"], e
v = s["validation"]
assert v["after"]["position_rms"] * 3 < v["before"]["position_rms"], v
assert v["after"]["orientation_rms"] * 3 < v["before"]["orientation_rms"], v
assert s["usable_images"] == 18, s["usable_images"]
PY
  report=$out/results/report.html
  grep -q "O2 [0-9.e-]* (sigma_min / sigma_max: the conditioning of the identification Jacobian), O3 [0-9.e-]* $unit (sigma_min" "$report"
  [ "$(grep -c '<svg' "$report")" -eq 8 ]
  for section in Plan Registration "Per-corner diagnostics" Measurements Validation "Camera-frame residuals" Residuals \
      "Calibrated parameters"; do
    grep -q "<h2>$section" "$report"
  done
  # The per-corner diagnostics (docs/calibration.md): the field, the histogram,
  # the worst corners named from results/corner_residuals.csv, the coverage.
  grep -q "Reprojection residuals (projected − detected), arrows" "$report"
  grep -q "|residual| against noise of σ" "$report"
  grep -q "<h3>Worst corners</h3>" "$report" && grep -q "<h3>Coverage</h3>" "$report"
  worst=$(python3 -c '
import csv, math, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert len(rows) > 1000, len(rows)
print(max(rows, key=lambda r: math.hypot(float(r["dx_px"]), float(r["dy_px"])))["image"])' "$out/results/corner_residuals.csv")
  grep -q "<tr><td>$worst</td>" "$report"
  [ -s "$out/truth/robot.yaml" ] && [ -s "$out/plan.csv" ] && [ "$(ls "$out/images" | wc -l)" -eq 18 ]
  # Every step done, by content; a replaced image makes measure, calibrate and validate stale.
  "$hexcal" session status "$out" --json | python3 -c '
import json, sys
status = json.load(sys.stdin)
steps = status["steps"]
assert set(steps) >= {"robot", "plan", "measure", "calibrate", "validate"}, steps
assert set(steps.values()) == {"done"}, steps
assert set(status["why"]) == set(steps), status["why"]'
  first=$(ls "$out/images" | head -1) second=$(ls "$out/images" | sed -n 2p)
  cp "$out/images/$second" "$out/images/$first"
  "$hexcal" session status "$out" >"$dir/status"
  grep -q "measure   stale   1 of 18 to measure again: 1 image(s) changed" "$dir/status"
  grep -q "calibrate stale   images/$first changed since the results" "$dir/status"
done

# The session's target described with the wrong spacing: calibrate --session
# refuses with the diagnosis (exit 2) instead of failing in the registration.
wrong="$dir/inria-left-hand"
sed -e 's/^tag_spacing: .*/tag_spacing: 0.5/' "$(dirname "$0")/../../resources/targets/aprilgrid-6x6.yaml" >"$wrong/wrong.yaml"
sed -i 's/^target: aprilgrid-6x6$/target: wrong.yaml/' "$wrong/session.yaml"
code=0
"$hexcal" calibrate --session "$wrong" --force >/dev/null 2>"$dir/err" || code=$?
[ "$code" -eq 2 ]
grep -q "images that show the board fit it badly" "$dir/err"

# Text output: the figures a person reads.
"$hexcal" demo --poses 14 --holdout 4 --seed 3 --out "$dir/inria-left-hand" --force >"$dir/text"
grep -q "within 3 sigma of the truth" "$dir/text" && grep -q "before calibration: position" "$dir/text"
if "$hexcal" demo --poses 14 --holdout 4 --out "$dir/inria-left-hand" 2>"$dir/err"; then exit 1; fi
grep -q "exists; use --force" "$dir/err"
mkdir -p "$dir/mine" && echo keep >"$dir/mine/notes.txt"
if "$hexcal" demo --poses 14 --holdout 4 --out "$dir/mine" --force 2>"$dir/err"; then exit 1; fi
grep -q "is not a demo folder" "$dir/err" && [ -s "$dir/mine/notes.txt" ]
echo "demo: ok"
