#!/usr/bin/env bash
# study.sh HEXCAL: the section 8 study from the command line on a demo session
# of random poses (demo --random-poses --holdout 0): the same seed gives the
# same JSON whatever the thread count (timings aside), another seed other
# subsets; the JSON's fields; --plots writes Figs. 18 and 19 as SVG and PNG
# and refuses to overwrite them without --force; bad options exit 2.
set -euo pipefail
hexcal=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
"$hexcal" demo --poses 18 --holdout 0 --random-poses --seed 2 --out "$dir/session" --json >"$dir/demo.json" 2>/dev/null
grep -q '"random_poses": true' "$dir/demo.json"
grep -q '"validation": null' "$dir/demo.json"
[ ! -e "$dir/session/plan_history.csv" ]
[ "$(grep -c ',0$' "$dir/session/legs.csv")" -eq 18 ]  # nothing held out

study=(study --session "$dir/session" --select 9 --subsets 200 --json)
# The JSON without its timings, thread count and date, keys sorted.
strip() { python3 -c 'import json,sys; j=json.load(sys.stdin); [j.pop(k) for k in ("seconds","subsets_seconds","threads","created")]; print(json.dumps(j, sort_keys=True))'; }
"$hexcal" "${study[@]}" --seed 3 --threads 1 | strip >"$dir/a.json"
"$hexcal" "${study[@]}" --seed 3 --threads 2 | strip >"$dir/b.json"
"$hexcal" "${study[@]}" --seed 4 | strip >"$dir/c.json"
cmp "$dir/a.json" "$dir/b.json"
! cmp -s "$dir/a.json" "$dir/c.json"
python3 - "$dir/a.json" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
assert j["measured"] == 18 and j["select"] == 9 and j["subsets"] == 200, j
assert j["criterion"] == "O1" and j["secondary"] is None and j["weighted_selection"] is True
s, r = j["selected"], j["random"]
assert len(s["poses"]) == 9 and len(s["images"]) == 9 and s["ok"]
assert 0 <= s["percentile"] <= 100 and s["percentile"] == s["percentiles"]["heldout_position_rms"]
assert set(s["percentiles"]) == {"O1", "O2", "O3", "O4", "heldout_position_rms", "heldout_orientation_rms"}
assert r["count"] == 200 and r["failed"] == 0
for key in ("O1", "O4", "heldout_position_rms", "heldout_orientation_rms"):
    d = r[key]
    assert d["count"] == 200 and d["min"] <= d["p5"] <= d["median"] <= d["p95"] <= d["max"], (key, d)
assert s["heldout_position_rms"] > 0
PY

"$hexcal" study --session "$dir/session" --select 9 --subsets 20 --unweighted-selection --criterion O4 --json |
  python3 -c 'import json,sys; j=json.load(sys.stdin); assert j["weighted_selection"] is False and j["criterion"] == "O4", j'
"$hexcal" study --session "$dir/session" --select 9 --subsets 100 --criterion O1 --secondary O4 \
  --plots "$dir/plots" >"$dir/text"
grep -q "^selected: IOOPS on O1, secondary O4 (rows weighted by the session.s noise model), 9 of the measured poses" "$dir/text"
grep -q "validates better than .* % of the random subsets" "$dir/text"
grep -q "^held-out position RMS (cm) " "$dir/text"
# O1..O4 with their unit and meaning (issue 39).
grep -q "^O1 (cm) " "$dir/text" && grep -q "^O2 (a ratio) " "$dir/text" && grep -q "^O4 (cm) " "$dir/text"
grep -q "^(O1..O4: the subset's observability indices, larger is better: O1 the volume" "$dir/text"
for figure in fig18_o1 fig18_o2 fig18_o3 fig18_o4 fig19_position fig19_orientation; do
  grep -q "</svg>" "$dir/plots/$figure.svg"
  [ "$(head -c 8 "$dir/plots/$figure.png" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ]
done
if "$hexcal" study --session "$dir/session" --select 9 --subsets 10 --plots "$dir/plots" 2>"$dir/err"; then exit 1; fi
grep -q "exists; use --force" "$dir/err"
"$hexcal" study --session "$dir/session" --select 9 --subsets 10 --plots "$dir/plots" --force >/dev/null

# The study is kept in the session: what --json printed is study/study.json,
# with its figures; --no-save prints without touching it; the report shows
# it, and marks it stale once a reading changes.
"$hexcal" study --session "$dir/session" --select 9 --subsets 50 --json >"$dir/kept.json"
cmp "$dir/kept.json" "$dir/session/study/study.json"
python3 - "$dir/kept.json" "$dir/session" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
assert j["format"] == 1 and j["saved"] == sys.argv[2] + "/study" and j["subsets"] == 50, j["saved"]
assert len(j["inputs"]) == 18 + 5 and len(j["inputs"]["legs.csv"]) == 64, sorted(j["inputs"])
PY
[ "$(wc -l <"$dir/session/study/subsets.csv")" -eq 52 ]  # header, the selected subset, 50 random ones
for figure in fig18_o1 fig18_o2 fig18_o3 fig18_o4 fig19_position fig19_orientation; do
  grep -q "</svg>" "$dir/session/study/$figure.svg"
  [ -s "$dir/session/study/$figure.png" ]
done
"$hexcal" study --session "$dir/session" --select 9 --subsets 20 --no-save --json |
  python3 -c 'import json,sys; j=json.load(sys.stdin); assert j["saved"] is None and j["subsets"] == 20, j["saved"]'
cmp "$dir/kept.json" "$dir/session/study/study.json"
! "$hexcal" study --session "$dir/session" --select 9 --subsets 20 --no-save | grep -q "study kept in"
"$hexcal" report --session "$dir/session" --out "$dir/page.html" >/dev/null
grep -q '<h2 id="study">Section 8 study</h2>' "$dir/page.html"
grep -q "validates better than .* % of the random subsets" "$dir/page.html"
! grep -q "Stale study" "$dir/page.html"
python3 - "$dir/session/legs.csv" <<'PY'  # L1 of the first image moved by 1e-6
import sys
lines = open(sys.argv[1]).read().split("\n")
cells = lines[1].split(",")
cells[1] = repr(float(cells[1]) + 1e-6)
lines[1] = ",".join(cells)
open(sys.argv[1], "w").write("\n".join(lines))
PY
"$hexcal" report --session "$dir/session" --out "$dir/page.html" --force >/dev/null
grep -q "<b>Stale study.</b> legs.csv changed after this study was made" "$dir/page.html"

code=0; "$hexcal" study --session "$dir/session" --select 18 2>"$dir/err" || code=$?
[ "$code" -eq 2 ] && grep -q "the session has 18" "$dir/err"
code=0; "$hexcal" study --session "$dir/session" --select 9 --criterion O9 2>"$dir/err" || code=$?
[ "$code" -eq 2 ] && grep -q "\-\-criterion: O9 not in {O1,O2,O3,O4,D,A,E,S}" "$dir/err"
[ -z "$(find "$dir" -name '.*tmp*')" ]
echo "ok: study determinism, JSON, text, figures and bad options"
