#!/usr/bin/env bash
# points_session.sh HEXCAL: a laser-tracker session from init to a verdict
# (issue 38; docs/calibration.md, "Point measurements").
# - `demo --instrument points` on both robots (4 reflectors, σ 0.02 mm per
#   coordinate, SpatialAnalyzer ASCII), calibrated from the points and with
#   --two-stage: ≥ 95 % of the parameters within 3σ of the truth, a verdict,
#   held-out error far below the nominal robot's, the calibration from points
#   at least as accurate as the two-stage one; its results/ files,
#   --keep-reflectors, and --from-pixels refused;
# - the same points by hand: `session init --instrument points` without a
#   reflector file (the reflectors estimated from the poses) → calibrated;
# - `session check-noise` on 30 simulated repeats reports the simulated σ
#   within 20 %, and a declared σ half the truth as optimistic;
# - the camera's: 12 renders of one pose against the board poses' covariance;
# - bad files: a point 1 m off, a pose with 2 points, a point twice, NaN, a
#   pose legs.csv names that the points file lacks, points in mm for a cm robot;
# - `session record` (images only) refuses a points session.
set -eu
hexcal=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
fail() { echo "$1"; cat "$2"; exit 1; }

for robot in inria-left-hand deltalab-table; do
  "$hexcal" demo --instrument points --robot "$robot" --out "$dir/$robot" --json >"$dir/$robot.json" 2>"$dir/$robot.log" ||
    fail "demo --instrument points --robot $robot failed" "$dir/$robot.log"
  "$hexcal" demo --instrument points --two-stage --robot "$robot" --out "$dir/$robot-two-stage" --json \
    >"$dir/$robot-two-stage.json" 2>"$dir/$robot-two-stage.log" ||
    fail "demo --instrument points --two-stage --robot $robot failed" "$dir/$robot-two-stage.log"
  python3 - "$dir/$robot.json" "$dir/$robot-two-stage.json" "$dir/$robot/results/report.json" <<'PY' ||
import json, sys
r = json.load(open(sys.argv[1]))
two = json.load(open(sys.argv[2]))
report = json.load(open(sys.argv[3]))
assert r["instrument"] == "points", r["instrument"]
assert r["from_points"] and not two["from_points"], (r["from_points"], two["from_points"])
assert report["method"] == "from-points", report["method"]
fit = report["from_points"]
assert fit["identifiability"]["rank"] == fit["identifiability"]["unknowns"] == 48, fit["identifiability"]
assert fit["reflectors_estimated"] and len(fit["reflectors"]) == 4, fit["reflectors"]
for x in (r, two):
    assert x["within_3sigma"] >= 0.95, x["within_3sigma"]
    v = x["validation"]
    assert v["after"]["position_rms"] < 0.2 * v["before"]["position_rms"], v
    assert x["verdict"]["level"] in ("good", "acceptable"), x["verdict"]
# The calibration from points is at least as accurate as the two-stage one (seed 1: 13 % and 41 % better).
assert r["parameter_error"]["mean"] <= 1.05 * two["parameter_error"]["mean"], (r["parameter_error"], two["parameter_error"])
v = r["validation"]
print("%s: within 3 sigma %.3f, parameter error mean %.3g (two-stage %.3g, nominal %.3g), held-out %.3g -> %.3g %s, "
      "verdict %s" % (sys.argv[1].split("/")[-1][:-5], r["within_3sigma"], r["parameter_error"]["mean"],
                      two["parameter_error"]["mean"], r["parameter_error"]["nominal_mean"], v["before"]["position_rms"],
                      v["after"]["position_rms"], r["length_unit"], r["verdict"]["level"]))
PY
    fail "$robot: figures" "$dir/$robot.json"
  [ -s "$dir/$robot/results/reflectors.csv" ] && [ -s "$dir/$robot/results/point_residuals.csv" ] ||
    fail "$robot: results/reflectors.csv, point_residuals.csv" "$dir/$robot.log"
done

# The other instrument's joint fit by name: bad input (exit 2), results/ untouched.
code=0; "$hexcal" calibrate --session "$dir/inria-left-hand" --from-pixels >"$dir/pixels.txt" 2>&1 || code=$?
[ "$code" = 2 ] && grep -q "a points session has no pixels; --from-points fits the measured points themselves" \
  "$dir/pixels.txt" || fail "--from-pixels on a points session (exit $code)" "$dir/pixels.txt"
# --keep-reflectors: 42 unknowns, the reflectors as the file gives them.
"$hexcal" calibrate --session "$dir/inria-left-hand" --from-points --keep-reflectors --json >"$dir/kept.json" 2>"$dir/kept.log" ||
  fail "--from-points --keep-reflectors" "$dir/kept.log"
python3 -c 'import json, sys; f = json.load(open(sys.argv[1]))["from_points"]; assert not f["reflectors_estimated"] and f["identifiability"]["unknowns"] == 42, f' "$dir/kept.json"
"$hexcal" session status "$dir/inria-left-hand" >"$dir/status.txt"
grep -q "^  measure   done    32 point sets, 4 reflectors$" "$dir/status.txt" || fail "status" "$dir/status.txt"
grep -q "^  calibrate done " "$dir/status.txt" || fail "status" "$dir/status.txt"

# By hand: the demo's points and readings, no reflector file.
demo=$dir/inria-left-hand
"$hexcal" session init --robot inria-left-hand --instrument points --points points.txt "$dir/hand" >"$dir/init.txt"
grep -q "put the measured points in $dir/hand/points.txt" "$dir/init.txt" || fail "init" "$dir/init.txt"
cp "$demo/points.txt" "$demo/legs.csv" "$dir/hand/"
"$hexcal" calibrate --session "$dir/hand" >"$dir/hand.txt" 2>&1 || fail "calibrate by hand" "$dir/hand.txt"
grep -q "^Verdict: \(good\|acceptable\)$" "$dir/hand.txt" || fail "by hand: verdict" "$dir/hand.txt"
"$hexcal" session status "$dir/hand" | grep -q "4 reflectors (estimated from the poses)"
"$hexcal" report --session "$dir/hand" --out "$dir/hand.html" >/dev/null

# With a reflector file, init derives the pose noise the planner weighs by.
"$hexcal" session init --robot inria-left-hand --instrument points --points points.txt \
  --reflectors "$demo/reflectors.csv" "$dir/refl" >"$dir/init2.txt"
grep -q "^noise: position: 0.00[0-9]*, angle_deg: 0.0[0-9]*, leg: 0.001 (position and angle_deg from the reflectors and --point-sigma); plan with hexcal plan --session $dir/refl --out $dir/refl/plan.csv$" "$dir/init2.txt" ||
  fail "init with reflectors" "$dir/init2.txt"

# session record writes images' rows: refused in a points session, legs.csv untouched.
cp "$dir/hand/legs.csv" "$dir/legs_before.csv"
if "$hexcal" session record "$dir/hand" --image a.png --legs 1,2,3,4,5,6 >"$dir/record.txt" 2>&1; then
  fail "session record in a points session was not refused" "$dir/record.txt"
fi
grep -q "is a points session: its legs.csv rows are poses (pose,L1..L6,holdout), not images" "$dir/record.txt" ||
  fail "session record: message" "$dir/record.txt"
cmp -s "$dir/hand/legs.csv" "$dir/legs_before.csv" || fail "session record changed legs.csv" "$dir/hand/legs.csv"
[ ! -e "$dir/hand/images/a.png" ] || fail "session record wrote an image" "$dir/record.txt"

# measure --points: every pose fitted, outside a session.
"$hexcal" measure --points "$demo/points.txt" --reflectors "$demo/reflectors.csv" --point-sigma 0.002 \
  --out "$dir/tracker_poses.csv" >"$dir/measure.txt"
grep -q "^measured 32 of 32 poses from their points; wrote" "$dir/measure.txt" || fail "measure --points" "$dir/measure.txt"
python3 - "$dir/tracker_poses.csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert len(rows) == 32 and all(r["status"] == "ok" and r["points"] == "4" for r in rows), rows[0]
assert max(float(r["rms"]) for r in rows) < 0.006, max(float(r["rms"]) for r in rows)  # 4 points, sigma 0.002 cm
PY

# Repeatability: 30 sets of one pose, σ 0.002 cm; declared as the session's σ, then as half of it.
python3 - "$demo/reflectors.csv" "$dir/repeats.txt" 0.002 <<'PY'
import csv, math, random, sys
random.seed(5)
refl = [(r["point"], float(r["x"]), float(r["y"]), float(r["z"])) for r in csv.DictReader(open(sys.argv[1]))]
sigma = float(sys.argv[3])
with open(sys.argv[2], "w") as out:
    for k in range(30):
        a = 0.3 + 1e-4 * k  # the same pose, the tracker bumped a little
        for name, x, y, z in refl:
            p = (math.cos(a) * x - math.sin(a) * y + 10, math.sin(a) * x + math.cos(a) * y - 4, z + 70)
            out.write("tracker rep%02d %s %s\n" % (k, name, " ".join("%.6f" % (c + random.gauss(0, sigma)) for c in p)))
PY
"$hexcal" session check-noise "$dir/hand" --points "$dir/repeats.txt" --json >"$dir/check.json"
python3 -c 'import json, sys; c = json.load(open(sys.argv[1])); assert abs(c["measured_sigma"] / 0.002 - 1) < 0.2, c; assert c["judgement"] == "good", c' "$dir/check.json"
grep -q '"noise_check.json"' "$dir/hand/results/manifest.json" && { echo "no check yet at calibration"; exit 1; }
"$hexcal" session status "$dir/hand" | grep -q "^  calibrate stale   noise_check.json changed" || { "$hexcal" session status "$dir/hand"; exit 1; }
sed -i 's/^point_sigma: .*/point_sigma: 0.001/' "$dir/hand/session.yaml"
"$hexcal" session check-noise "$dir/hand" --points "$dir/repeats.txt" >"$dir/check.txt"
grep -q "ratio measured/declared 2.*: optimistic" "$dir/check.txt" || fail "half the sigma declared" "$dir/check.txt"

# The camera's repeatability: 12 renders of one board pose (the renderer's
# noise differs per image) against the board poses' own covariances.
"$hexcal" demo --two-stage --poses 8 --holdout 0 --random-poses --out "$dir/cam" >/dev/null 2>&1
python3 - "$dir/cam/camera_poses.csv" "$dir/still.csv" <<'PY'
import csv, sys
r = next(csv.DictReader(open(sys.argv[1])))
row = ",".join(r[k] for k in ["x", "y", "z", "q1", "q2", "q3"])
open(sys.argv[2], "w").write("x,y,z,q1,q2,q3\n" + (row + "\n") * 12)
PY
"$hexcal" render --poses "$dir/still.csv" --out "$dir/still" >/dev/null
"$hexcal" session check-noise "$dir/cam" --images "$dir/still" --json >"$dir/cam_check.json"
python3 -c 'import json, sys; c = json.load(open(sys.argv[1])); assert c["repeats"] == 12 and 0.5 < c["ratio"] < 1.5, c' "$dir/cam_check.json"
code=0; "$hexcal" session check-noise "$dir/cam" --points "$dir/repeats.txt" 2>"$dir/wrong.txt" || code=$?
[ "$code" = 2 ] && grep -q "takes --images FOLDER" "$dir/wrong.txt" || fail "points for a camera session (exit $code)" "$dir/wrong.txt"

# Bad files: each a clear error (exit 2) or a named pose left out.
bad() {  # NAME, a sed script on points.txt; the expected message
  rm -rf "$dir/bad"; cp -r "$dir/hand" "$dir/bad"; rm -rf "$dir/bad/results" "$dir/bad/noise_check.json"
  sed -i "$2" "$dir/bad/points.txt"
  code=0; "$hexcal" calibrate --session "$dir/bad" >"$dir/bad.txt" 2>&1 || code=$?
  grep -q "$3" "$dir/bad.txt" || fail "$1: expected '$3' (exit $code)" "$dir/bad.txt"
  echo "$code"
}
[ "$(bad "1 m off" '/ pose_0003 R2 /s/ \([-0-9.]*\)$/ 100/' "pose 'pose_0003': point '.*' lies .* left out")" = 0 ]
[ "$(bad "2 points" '/ pose_0004 R[34] /d' "pose 'pose_0004': 2 points measured: a pose needs 3 or more reflectors; left out")" = 0 ]
[ "$(bad "twice" '/ pose_0005 R1 /p' "points.txt:[0-9]*: .*R1.* twice")" = 2 ]
[ "$(bad "NaN" '/ pose_0006 R1 /s/ \([-0-9.]*\)$/ nan/' "points.txt:[0-9]*: field 6 is not a number")" = 2 ]
[ "$(bad "missing pose" '/ pose_0007 /d' "legs.csv:9: pose 'pose_0007' has no points in")" = 2 ]
rm -rf "$dir/mm"; cp -r "$demo" "$dir/mm"; rm -rf "$dir/mm/results"
python3 - "$dir/mm/points.txt" <<'PY'
import sys
lines = open(sys.argv[1]).read().splitlines()
out = [l if l.startswith("//") else " ".join(l.split()[:3] + ["%.6f" % (10 * float(v)) for v in l.split()[3:]]) for l in lines]
open(sys.argv[1], "w").write("\n".join(out) + "\n")
PY
code=0; "$hexcal" calibrate --session "$dir/mm" >"$dir/mm.txt" 2>&1 || code=$?
[ "$code" = 2 ] && grep -q "another length unit" "$dir/mm.txt" || fail "points in mm for a cm robot (exit $code)" "$dir/mm.txt"
echo "points session: ok"
