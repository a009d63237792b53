#!/usr/bin/env bash
# plan_determinism.sh HEXCAL: the same seed gives the same plan; the plan has the
# documented columns and N rows; its indices beat the random start's.
set -eu
hexcal=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
args=(plan --robot inria-left-hand --poses 18 --candidate-kind random --candidate-count 400 --addfind-starts 100 --tabu 3
      --iterations 30)
"$hexcal" "${args[@]}" --seed 5 --out "$dir/a.csv" --json >"$dir/a.json"
"$hexcal" "${args[@]}" --seed 5 --out "$dir/b.csv" --json >/dev/null
cmp "$dir/a.csv" "$dir/b.csv"
head -1 "$dir/a.csv" | grep -qx "x,y,z,q1,q2,q3,L1,L2,L3,L4,L5,L6"
[ "$(wc -l <"$dir/a.csv")" -eq 19 ]
python3 - "$dir/a.json" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
for k in ("O1", "O2", "O3", "O4"):
    assert d["final"][k] > d["initial"][k], (k, d["initial"][k], d["final"][k])
PY
echo "ok: plan determinism"
