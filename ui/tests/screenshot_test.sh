#!/usr/bin/env bash
# screenshot_test.sh HEXCAL_GUI SESSIONS: `hexcal-gui --screenshot` writes a PNG of
# every panel of the calibrated session at the size asked for, 1280x720 (the
# Acquire panel connected to the sim devices; `study`, the Validate step's
# study tab), and refuses a bad panel, size or folder. Whether every panel
# fits that size is ui/tests/fit_test.cc's check.
set -eu
gui=$1 sessions=$2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
for panel in robot plan acquire measure calibrate validate study; do
  devices=()
  [ "$panel" = acquire ] && devices=(--controller sim --camera sim)
  "$gui" --screenshot "$dir/$panel.png" --panel "$panel" --size 1280x720 "${devices[@]}" "$sessions/calibrated"
  python3 - "$dir/$panel.png" <<'PY'
import struct, sys
data = open(sys.argv[1], 'rb').read()
assert data[:8] == b'\x89PNG\r\n\x1a\n', 'not a PNG'
width, height = struct.unpack('>II', data[16:24])
assert (width, height) == (1280, 720), (sys.argv[1], width, height)
PY
done
if "$gui" --screenshot "$dir/x.png" --panel nope "$sessions/calibrated" 2>"$dir/err"; then exit 1; fi
grep -q "is not robot, plan" "$dir/err"
if "$gui" --screenshot "$dir/x.png" --size 12x "$sessions/calibrated" 2>"$dir/err"; then exit 1; fi
grep -q "is not WIDTHxHEIGHT" "$dir/err"
if "$gui" --screenshot "$dir/x.png" "$dir/no-such-session" 2>"$dir/err"; then exit 1; fi
grep -q "Open session" "$dir/err"
