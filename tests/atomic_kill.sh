#!/usr/bin/env bash
# atomic_kill.sh WRITER WORKDIR [ROUNDS]: kill -9 a process in the middle of
# WriteFileAtomically, many times, and check that the target file is always one
# complete generation: the last one the writer reported, or the one it was
# renaming when it died. WRITER is tests/atomic_writer.cc (see there for the
# file format). Also checks that a killed writer leaves at most its one in-flight
# temp file (.NAME.tmp.XXXXXX) behind and that a writer that finishes leaves none.
# Stale temp files of a killed writer are not cleaned by hexcal; this script
# removes them between rounds (docs/hardening.md).
set -u
writer=$1 workdir=$2 rounds=${3:-40}
megabytes=8
mkdir -p "$workdir"
dir=$(mktemp -d "$workdir/atomic_kill.XXXXXX")
trap 'rm -rf "$dir"' EXIT
target=$dir/plan.bin
fail() { echo "FAIL: $*"; exit 1; }

temp_files() { find "$dir" -maxdepth 1 -name '.plan.bin.tmp.*' | wc -l; }
on_disk() { "$writer" check "$target" | sed -n 's/^generation //p'; }

"$writer" write "$target" "$megabytes" 1 1 >/dev/null || fail "first write"
generation=$(on_disk)
[ "$generation" = 1 ] || fail "first write gave generation '$generation'"

mid_write=0
for round in $(seq "$rounds"); do
  first=$((generation + 1))
  "$writer" write "$target" "$megabytes" "$first" >"$dir/log" 2>&1 &
  pid=$!
  sleep "0.$(printf '%03d' $((RANDOM % 400 + 20)))"
  kill -KILL "$pid"
  wait "$pid" 2>/dev/null
  code=$?
  [ "$code" = 137 ] || fail "round $round: writer exited with $code before the kill: $(cat "$dir/log")"

  last=$(sed -n 's/^wrote //p' "$dir/log" | tail -n 1)
  last=${last:-$generation}  # nothing finished: the previous file must still be there
  found=$("$writer" check "$target" 2>&1) || fail "round $round: torn file after kill -9: $found"
  found=${found#generation }
  # The rename may have landed before "wrote N" was printed, so N+1 is allowed too.
  if [ "$found" != "$last" ] && [ "$found" != $((last + 1)) ]; then
    fail "round $round: file holds generation $found, expected $last or $((last + 1))"
  fi

  temps=$(temp_files)
  [ "$temps" -le 1 ] || fail "round $round: $temps temp files left, at most the in-flight one allowed"
  if [ "$temps" = 1 ]; then
    mid_write=$((mid_write + 1))
    rm -f "$dir"/.plan.bin.tmp.*
  fi
  generation=$found
done

# Without a kill landing inside a write the test would prove nothing.
[ "$mid_write" -ge 1 ] || fail "no kill out of $rounds landed inside a write"

"$writer" write "$target" "$megabytes" $((generation + 1)) 3 >/dev/null || fail "final writes"
[ "$(on_disk)" = $((generation + 3)) ] || fail "final writes did not land"
[ "$(temp_files)" = 0 ] || fail "a writer that finished left temp files"
echo "ok: $rounds kills, $mid_write inside a write, file always complete"
