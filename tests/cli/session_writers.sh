#!/usr/bin/env bash
# session_writers.sh HEXCAL: one writer per session (docs/session.md, "One
# writer at a time").
#   1. A second `calibrate --session` while one runs stops at once, exit 3,
#      naming the first one's PID and command; `--wait` waits and succeeds.
#   2. A writer killed with -9 leaves no lock behind: the next run goes on.
#   3. Three processes record 30 rows into legs.csv at once, while a
#      calibration waits its turn: every row of every writer is kept.
set -u
hexcal=$1
work=$(mktemp -d)
trap 'kill $(jobs -p) 2>/dev/null; rm -rf "$work"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

"$hexcal" demo --out "$work/s" --poses 12 --holdout 2 --seed 4 >/dev/null 2>&1 || fail "demo"
s=$work/s
wait_for_lock() {  # the lock file names a holder
  for _ in $(seq 1500); do grep -q '^PID' "$s/.hexcal.lock" 2>/dev/null && return 0; sleep 0.02; done
  fail "no writer took the lock"
}

# 1. Re-measuring every image keeps the first run busy for a few seconds.
rm -f "$s/camera_poses.csv"
"$hexcal" calibrate --session "$s" >"$work/first.log" 2>&1 &
first=$!
wait_for_lock
"$hexcal" calibrate --session "$s" >"$work/second.log" 2>&1
code=$?
[ $code -eq 3 ] || fail "a second calibrate gave exit $code, not 3: $(cat "$work/second.log")"
grep -q "session in use by PID $first (hexcal calibrate --session" "$work/second.log" ||
  fail "the refusal does not name PID $first: $(cat "$work/second.log")"
"$hexcal" session record "$s" --image "$(ls "$s/images" | head -1)" --legs 1,2,3,1,2,3 --replace >"$work/rec.log" 2>&1
[ $? -eq 3 ] || fail "session record during a calibration was not refused"
"$hexcal" calibrate --session "$s" --wait >"$work/waited.log" 2>&1 || fail "calibrate --wait: $(cat "$work/waited.log")"
wait $first || fail "the first calibrate failed: $(cat "$work/first.log")"
echo "second writer: exit 3 naming PID $first; --wait waited and succeeded"

# 2. kill -9 in the middle of a run.
rm -f "$s/camera_poses.csv"
"$hexcal" calibrate --session "$s" >/dev/null 2>&1 &
victim=$!
wait_for_lock
kill -9 $victim
wait $victim 2>/dev/null
"$hexcal" calibrate --session "$s" >"$work/after.log" 2>&1 || fail "after a kill -9: $(cat "$work/after.log")"
"$hexcal" report --session "$s" --out "$work/r.html" >/dev/null 2>&1 || fail "results/ not whole after a kill -9"
echo "writer killed with -9: the next run took the lock at once"

# 3. Concurrent recorders: copies of one image with that image's readings.
first_image=$(sed -n 2p "$s/legs.csv" | cut -d, -f1)
readings=$(grep "^$first_image," "$s/legs.csv" | cut -d, -f2-7)
record_many() {  # PREFIX
  for i in $(seq -w 1 10); do
    "$hexcal" session record "$s" --image "$1_$i.png" --from "$s/images/$first_image" --legs "$readings" --wait \
      >/dev/null 2>>"$work/errors.log" ||
      echo "$1_$i failed" >>"$work/errors.log"
  done
}
before=$(($(wc -l <"$s/legs.csv") - 1))
record_many a &
writers=$!
record_many b &
writers="$writers $!"
record_many c &
writers="$writers $!"
"$hexcal" calibrate --session "$s" --wait >/dev/null 2>>"$work/errors.log" &
writers="$writers $!"
for pid in $writers; do wait "$pid"; done
[ ! -s "$work/errors.log" ] || fail "concurrent writers: $(cat "$work/errors.log")"
after=$(($(wc -l <"$s/legs.csv") - 1))
[ $after -eq $((before + 30)) ] || fail "legs.csv has $after rows, expected $before + 30"
for p in a b c; do
  [ "$(grep -c "^${p}_" "$s/legs.csv")" -eq 10 ] || fail "rows of writer $p lost"
done
"$hexcal" calibrate --session "$s" >/dev/null 2>&1 || fail "calibrate after the concurrent writers"
echo "3 recorders and a calibration at once: all $((after - before)) new rows kept"
