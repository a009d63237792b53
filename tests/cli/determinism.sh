#!/usr/bin/env bash
# determinism.sh HEXCAL: the same seed gives the same candidates, another seed others;
# a written file is complete and no temporary file is left behind.
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
echo "ok: determinism and ik"
