#!/usr/bin/env bash
# kill_writes.sh HEXCAL SHIM: kill -9 `hexcal calibrate --session` and
# `hexcal session record` (the GUI's capture and cell edits go through the same
# workflow/session_edits.h) just before each of their file-system changes in
# turn: run N is killed before its Nth change (SHIM is tests/kill_at_call.c),
# N = 1, 2, ... until a run finishes. After every kill:
#   - the recorded inputs (images/, plan.csv, legs.csv but for the new row) are
#     byte for byte as before;
#   - results/ is one whole unit: `hexcal report` checks every file against
#     results/manifest.json, and it is the old unit or a new one, never a mix;
#   - the next run is not refused: the dead writer's lock is free.
set -u
hexcal=$1 shim=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
sums() { (cd "$1" && find images plan.csv -type f -print0 | sort -z | xargs -0 sha256sum); }

"$hexcal" demo --out "$work/base" --poses 8 --holdout 2 --seed 3 >/dev/null 2>&1 || fail "demo"
base=$work/base
sums "$base" >"$work/inputs.sum"
old_created=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["created"])' "$base/results/manifest.json")
sleep 1  # a new unit's "created" differs from the old one's

check_session() {  # DIR WHAT
  local dir=$1 what=$2
  [ "$(sums "$dir")" = "$(cat "$work/inputs.sum")" ] || fail "$what: images/ or plan.csv changed"
  "$hexcal" report --session "$dir" --out "$work/page.html" --force >"$work/report.log" 2>&1 ||
    fail "$what: results/ is not one whole unit: $(cat "$work/report.log")"
}

kills=0
for n in $(seq 1 200); do
  rm -rf "$work/s" && cp -a "$base" "$work/s"
  HEXCAL_KILL_AT=$n LD_PRELOAD=$shim "$hexcal" calibrate --session "$work/s" >/dev/null 2>&1
  code=$?
  if [ $code -eq 0 ]; then break; fi
  [ $code -eq 137 ] || fail "calibrate with a kill at change $n: exit $code, not killed"
  kills=$((kills + 1))
  check_session "$work/s" "calibrate killed before change $n"
  cmp -s "$base/legs.csv" "$work/s/legs.csv" || fail "calibrate killed before change $n: legs.csv changed"
  created=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["created"])' "$work/s/results/manifest.json")
  # The old unit, file for file, or a new one (which `report` checked whole).
  if [ "$created" = "$old_created" ]; then
    diff -r "$base/results" "$work/s/results" >/dev/null || fail "calibrate killed before change $n: old manifest, other files"
  fi
  "$hexcal" calibrate --session "$work/s" >"$work/again.log" 2>&1 || fail "rerun after a kill at change $n: $(cat "$work/again.log")"
  check_session "$work/s" "rerun after a kill at change $n"
  [ -z "$(find "$work/s" -maxdepth 1 -name '.results.new-*')" ] || fail "rerun after a kill at change $n left a staging folder"
  [ $n -lt 200 ] || fail "calibrate --session was still killed at change 200"
done
[ $kills -ge 10 ] || fail "calibrate --session made only $kills file-system changes: is the shim loaded?"
echo "calibrate --session: killed before each of its $kills file-system changes; results/ always whole"

# session record --from (the GUI's capture: the image and its row together):
# legs.csv keeps every old row and has the new one or not; an image without
# its row is named by the next command, never silently used.
frame=$work/frame.png
cp "$base/images/$(ls "$base/images" | head -1)" "$frame"
record_kills=0
for n in $(seq 1 50); do
  rm -rf "$work/s" && cp -a "$base" "$work/s"
  HEXCAL_KILL_AT=$n LD_PRELOAD=$shim "$hexcal" session record "$work/s" --image extra.png --from "$frame" \
    --legs 1,2,3,1,2,3 >/dev/null 2>&1
  code=$?
  if [ $code -eq 0 ]; then break; fi
  [ $code -eq 137 ] || fail "session record with a kill at change $n: exit $code"
  record_kills=$((record_kills + 1))
  python3 - "$base/legs.csv" "$work/s/legs.csv" <<'PY' || fail "session record killed before change $n: legs.csv lost rows"
import sys
old = open(sys.argv[1]).read().splitlines()[1:]
new = open(sys.argv[2]).read().splitlines()[1:]
rows = [r for r in new if not r.startswith('extra.png,')]
sys.exit(0 if len(new) - len(rows) <= 1 and sorted(r.split(',')[0] for r in rows) == sorted(r.split(',')[0] for r in old) else 1)
PY
  if [ -e "$work/s/images/extra.png" ] && ! grep -q '^extra.png,' "$work/s/legs.csv"; then
    "$hexcal" session status "$work/s" | grep -q "images/extra.png: no row in" ||
      fail "an image left without its row by a kill at change $n is not named"
    rm "$work/s/images/extra.png"
  fi
  if ! grep -q '^extra.png,' "$work/s/legs.csv"; then
    "$hexcal" session record "$work/s" --image extra.png --from "$frame" --legs 1,2,3,1,2,3 >/dev/null 2>&1 ||
      fail "record after a kill at change $n refused"
  fi
  [ $n -lt 50 ] || fail "session record was still killed at change 50"
done
[ $record_kills -ge 3 ] || fail "session record made only $record_kills changes"
grep -q '^extra.png,1,2,3,1,2,3' "$work/s/legs.csv" || fail "the finished record did not write its row"
echo "session record: killed before each of its $record_kills file-system changes; legs.csv always whole"
