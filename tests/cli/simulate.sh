#!/usr/bin/env bash
# simulate.sh HEXCAL: the section 7 study from the command line: the same seed
# gives the same JSON whatever the thread count, another seed other numbers;
# --csv and --plots write the table and both figures as SVG and PNG.
set -eu
hexcal=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
"$hexcal" candidates --robot inria-left-hand --kind uniform --count 20 --seed 2 --out "$dir/fixed.csv" >/dev/null
study=(simulate --robot inria-left-hand --sets "random,$dir/fixed.csv" --poses 10 --runs 6 --json)
"$hexcal" "${study[@]}" --seed 3 --threads 1 >"$dir/a.json"
"$hexcal" "${study[@]}" --seed 3 --threads 2 >"$dir/b.json"
"$hexcal" "${study[@]}" --seed 4 >"$dir/c.json"
cmp "$dir/a.json" "$dir/b.json"
! cmp -s "$dir/a.json" "$dir/c.json"
grep -q '"before": {' "$dir/a.json"
grep -q '"ratio_to_random": 1.0' "$dir/a.json"
grep -q "\"name\": \"$dir/fixed.csv\"" "$dir/a.json"

"$hexcal" simulate --robot inria-left-hand --sets "random,$dir/fixed.csv" --poses 10 --runs 4 --sweep 8:12 \
  --csv "$dir/table.csv" --plots "$dir/plots" >"$dir/report.txt"
grep -q "Fig. 15: error against the number of poses" "$dir/report.txt"
head -1 "$dir/table.csv" | grep -q "^study,name,poses,mean,std,ratio_to_random$"
[ "$(grep -c '^sweep,' "$dir/table.csv")" -eq 10 ]
for figure in fig14 fig15_mean fig15_std; do
  grep -q "</svg>" "$dir/plots/$figure.svg"
  [ "$(head -c 8 "$dir/plots/$figure.png" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ]
done
[ -z "$(find "$dir" -name '.*tmp*')" ]
echo "ok: simulate determinism, table and figures"
