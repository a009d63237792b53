#!/usr/bin/env bash
# determinism.sh HEXCAL: the same seed gives the same candidates, another seed others;
# a written file is complete and no temporary file is left behind; two runs
# of a demo calibrate to the same parameters.
set -eu
hexcal=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
"$hexcal" candidates --robot inria-left-hand --kind random --count 50 --seed 7 --out "$dir/a.csv" >/dev/null
"$hexcal" candidates --robot inria-left-hand --kind random --count 50 --seed 7 --out "$dir/b.csv" >/dev/null
"$hexcal" candidates --robot inria-left-hand --kind random --count 50 --seed 8 --out "$dir/c.csv" >/dev/null
cmp "$dir/a.csv" "$dir/b.csv"
! cmp -s "$dir/a.csv" "$dir/c.csv"
[ "$(wc -l <"$dir/a.csv")" -eq 51 ]
[ -z "$(find "$dir" -name '.*tmp*')" ]
# ik on those poses: every pose feasible, 50 rows of readings.
"$hexcal" ik --robot inria-left-hand --poses "$dir/a.csv" --out "$dir/legs.csv" | grep -q "50 poses, 50 feasible"
head -1 "$dir/legs.csv" | grep -q "L1,L2,L3,L4,L5,L6"
# The calibrations from pixels and from points run Ceres on one thread: two
# runs of a demo give the same parameters to the last digit (a multi-threaded
# evaluation sums in the order its threads finish: the 8th digit varied).
same_parameters() {
  python3 - "$1" "$2" <<'PY'
import json, sys
a, b = (json.load(open(f + "/results/report.json")) for f in sys.argv[1:])
sys.exit(0 if a["parameters"] == b["parameters"] and a["validation"] == b["validation"] else 1)
PY
}
for instrument in camera points; do
  for run in 1 2; do
    "$hexcal" demo --instrument "$instrument" --out "$dir/$instrument$run" >/dev/null
  done
  same_parameters "$dir/${instrument}1" "$dir/${instrument}2" || { echo "$instrument demo: two runs differ" >&2; exit 1; }
done
echo "ok: determinism and ik"
