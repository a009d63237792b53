#!/usr/bin/env bash
# calibration.sh HEXCAL DATA: the calibration workflow end to end against an
# independent truth (tests/data/measurements/inria_true.yaml, a perturbed INRIA
# robot): its exact leg readings at 30 poses, calibrated from the nominal robot,
# must give a robot file whose leg readings and forward kinematics match the
# truth, that loads into every command taking a robot, and that is never
# overwritten without --force.
set -eu
hexcal=$1 data=$2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
truth=$data/measurements/inria_true.yaml

# Largest |a - b| over columns first..last of two CSV files with the same layout (header skipped).
max_diff() {
  paste -d, "$1" "$2" | awk -F, -v first="$3" -v last="$4" -v width="$5" '
    NR > 1 { for (k = first; k <= last; ++k) { d = $k - $(k + width); if (d < 0) d = -d; if (d > m) m = d } }
    END { printf "%.3g\n", m }'
}
# The "mean" of the "position" object in `hexcal validate --json` output.
position_mean() { awk '/"position": \{/ { p = 1 } p && /"mean"/ { gsub(/[",]/, ""); print $2; exit }' "$1"; }
below() { awk -v a="$1" -v b="$2" 'BEGIN { exit !(a < b) }'; }

"$hexcal" candidates --robot inria-left-hand --kind uniform --count 30 --seed 5 --out "$dir/poses.csv" >/dev/null
"$hexcal" ik --robot "$truth" --poses "$dir/poses.csv" --out "$dir/m.csv" >/dev/null

"$hexcal" calibrate --robot inria-left-hand --measurements "$dir/m.csv" --out "$dir/cal.yaml" >"$dir/report.txt"
grep -q "calibrated robot inria-left-hand from 30 measurements" "$dir/report.txt"
grep -q "^  1 l " "$dir/report.txt"

# An existing --out is kept unless --force is given.
cp "$dir/cal.yaml" "$dir/before.yaml"
code=0
"$hexcal" calibrate --robot inria-left-hand --measurements "$dir/m.csv" --out "$dir/cal.yaml" 2>"$dir/err" || code=$?
[ "$code" -eq 2 ]
grep -q "cal.yaml: exists; use --force to overwrite it" "$dir/err"
cmp "$dir/cal.yaml" "$dir/before.yaml"
"$hexcal" calibrate --robot inria-left-hand --measurements "$dir/m.csv" --out "$dir/cal.yaml" --force --json \
  >"$dir/cal.json"
grep -q '"termination": "CONVERGENCE"' "$dir/cal.json"
grep -q "^calibration:" "$dir/cal.yaml"

# The calibrated robot predicts the truth's leg readings (columns 7-12 of ik --out, 14 per file).
"$hexcal" ik --robot "$dir/cal.yaml" --poses "$dir/poses.csv" --out "$dir/cal_legs.csv" >/dev/null
diff=$(max_diff "$dir/m.csv" "$dir/cal_legs.csv" 7 12 14)
below "$diff" 1e-9 || { echo "FAIL: calibrated leg readings differ from the truth's by $diff"; exit 1; }

# Validation: the calibrated robot explains the measurements, the nominal one does not.
"$hexcal" validate --robot "$dir/cal.yaml" --measurements "$dir/m.csv" --json >"$dir/v_cal.json"
"$hexcal" validate --robot inria-left-hand --measurements "$dir/m.csv" --json >"$dir/v_nominal.json"
calibrated=$(position_mean "$dir/v_cal.json") nominal=$(position_mean "$dir/v_nominal.json")
below "$calibrated" 1e-8 || { echo "FAIL: calibrated FK position error $calibrated"; exit 1; }
below 0.01 "$nominal" || { echo "FAIL: nominal FK position error $nominal is not large"; exit 1; }
"$hexcal" validate --robot "$dir/cal.yaml" --measurements "$dir/m.csv" | grep -q "position (cm)"
# The verdict (docs/calibration.md, "Verdict"): errors against the noise model's prediction.
python3 -c 'import json, sys; v = json.load(open(sys.argv[1]))["verdict"]; assert v["level"] == "good", v' "$dir/v_cal.json"
"$hexcal" validate --robot inria-left-hand --measurements "$dir/m.csv" | grep -q "^Verdict: poor$"

# Every command that takes a robot takes the calibrated file.
"$hexcal" robot check "$dir/cal.yaml" | grep -q "is valid"
"$hexcal" robot show "$dir/cal.yaml" >/dev/null
"$hexcal" fk --robot "$dir/cal.yaml" --legs 1,1,1,1,1,1 --start 0,0,53,0,0,0 >/dev/null
"$hexcal" indices --robot "$dir/cal.yaml" --poses "$dir/poses.csv" >/dev/null
"$hexcal" candidates --robot "$dir/cal.yaml" --kind uniform --count 5 --out "$dir/c.csv" >/dev/null
"$hexcal" simulate --robot "$dir/cal.yaml" --sets random --poses 10 --runs 2 >/dev/null
"$hexcal" calibrate --robot "$dir/cal.yaml" --measurements "$dir/m.csv" --out "$dir/again.yaml" >/dev/null
"$hexcal" plan --robot "$dir/cal.yaml" --poses 8 --candidates "$dir/poses.csv" --no-certificate \
  --out "$dir/plan.csv" >/dev/null
echo "ok: calibration end to end (leg readings within $diff, FK $calibrated vs nominal $nominal)"
