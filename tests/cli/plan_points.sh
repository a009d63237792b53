#!/usr/bin/env bash
# plan_points.sh HEXCAL: `hexcal plan --session` on a laser-tracker session
# (issue 38; docs/planner.md, "Planning for a laser tracker").
# - session init with the tracker's position and σ law writes the tracker
#   section; plan --session weighs each pose by the tracker's covariance and
#   keeps every reflector in its line of sight: each planned pose's reflectors
#   are checked here, independently, to face the tracker within 30°;
# - the tracker below the platform: no candidate, exit 1, said why;
# - bad tracker flags are refused naming the key (exit 2).
set -eu
hexcal=$1
expect="$(dirname "$0")/expect.sh"
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
fail() { echo "$1"; cat "$2"; exit 1; }

printf 'point,x,y,z\nR1,7,0,1\nR2,-3.5,6,0.5\nR3,-3.5,-6,1.5\nR4,0,0.5,3\n' >"$dir/reflectors.csv"
init=("$hexcal" session init --robot inria-left-hand --instrument points --points points.txt
  --reflectors "$dir/reflectors.csv")
"${init[@]}" "$dir/s" --tracker-position 30,0,200 --tracker-sigma-law linear --tracker-sigma0 0.0015 \
  --tracker-sigma-per-distance 0.000006 --tracker-leg-radius 1 >"$dir/init.txt"
grep -q "plan with hexcal plan --session $dir/s --out $dir/s/plan.csv$" "$dir/init.txt" || fail "init" "$dir/init.txt"
grep -q "sigma_law: linear" "$dir/s/session.yaml" || fail "session.yaml" "$dir/s/session.yaml"

plan=(--poses 12 --candidate-kind random --candidate-count 2000 --no-certificate --polish 3)
"$hexcal" plan --session "$dir/s" --out "$dir/s/plan.csv" "${plan[@]}" >"$dir/plan.txt" 2>&1 ||
  fail "plan --session" "$dir/plan.txt"
grep -q "^  tracker: reflector σ 0.00[0-9]* to 0.00[0-9]* cm over the plan's poses, every reflector in its line of sight$" \
  "$dir/plan.txt" || fail "plan: tracker line" "$dir/plan.txt"
grep -q "^  predicted with each pose's covariance from the tracker" "$dir/plan.txt" || fail "plan: prediction" "$dir/plan.txt"
python3 - "$dir/s/plan.csv" <<'PY'
import csv, math, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert len(rows) == 12, len(rows)
tracker = (30.0, 0.0, 200.0)
reflectors = [(7, 0, 1), (-3.5, 6, 0.5), (-3.5, -6, 1.5), (0, 0.5, 3)]
def rot(axis, a):
    c, s = math.cos(a), math.sin(a)
    return {"x": [[1, 0, 0], [0, c, -s], [0, s, c]], "y": [[c, 0, s], [0, 1, 0], [-s, 0, c]],
            "z": [[c, -s, 0], [s, c, 0], [0, 0, 1]]}[axis]
def mul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(3)) for j in range(3)] for i in range(3)]
for r in rows:
    q = [math.radians(float(r[k])) for k in ("q1", "q2", "q3")]
    R = mul(rot("z", q[2]), mul(rot("y", q[1]), rot("x", q[0])))  # robot file: euler xyz
    P = [float(r[k]) for k in ("x", "y", "z")]
    normal = [R[i][2] for i in range(3)]
    for b in reflectors:
        p = [P[i] + sum(R[i][k] * b[k] for k in range(3)) for i in range(3)]
        d = [tracker[i] - p[i] for i in range(3)]
        cos = sum(normal[i] * d[i] for i in range(3)) / math.sqrt(sum(x * x for x in d))
        assert math.degrees(math.acos(min(1, cos))) <= 30 + 1e-6, (r, b, math.degrees(math.acos(cos)))
print("12 planned poses, every reflector within 30 deg of facing the tracker")
PY
"$hexcal" plan --session "$dir/s" --out "$dir/s/plan2.csv" "${plan[@]}" --json >"$dir/plan.json"
python3 - "$dir/plan.json" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
t = j["tracker"]
assert t["line_of_sight"] is True and 0 < t["reflector_sigma_min"] <= t["reflector_sigma_max"] < 0.003, t
assert j["predicted"]["valid"], j["predicted"]
PY

# The tracker below the platform sees no reflector: no candidate.
"${init[@]}" "$dir/below" --tracker-position 30,0,-100 >/dev/null
"$expect" 1 "satisf(y|ies) the robot and measurement constraints" -- \
  "$hexcal" plan --session "$dir/below" --out "$dir/below/plan.csv" "${plan[@]}"

# Bad flags, named.
"$expect" 2 "tracker.sigma_law: linear needs tracker.position" -- "${init[@]}" "$dir/bad1" --tracker-sigma-law linear --tracker-sigma0 0.001
"$expect" 2 "--tracker-sigma-per-distance: must be at most 0.001 unit per unit, got 0.01" -- "${init[@]}" "$dir/bad2" --tracker-position 0,0,100 --tracker-sigma-per-distance 0.01
"$expect" 2 "tracker-position" -- "${init[@]}" "$dir/bad3" --tracker-position 0,0
"$expect" 2 "are for points sessions" -- "$hexcal" session init --robot inria-left-hand --camera sim-4.2mm-1024x768 \
  --target aprilgrid-6x6 --tracker-position 0,0,100 "$dir/camera"
"$expect" 2 "excludes" -- "$hexcal" plan --robot inria-left-hand --session "$dir/s" --out "$dir/x.csv"
"$expect" 2 "give the robot \(--robot\) or a session \(--session\)" -- "$hexcal" plan --out "$dir/x.csv"
echo "plan_points: ok"
