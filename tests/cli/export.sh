#!/usr/bin/env bash
# export.sh HEXCAL: `hexcal export --format linuxcnc-hal` writes the genhexkins
# pins of a robot file in the machine's unit (inria-left-hand is in cm: mm
# values are ten times the file's, inch values 1/2.54 of them), refuses to
# overwrite without --force and names bad options.
set -eu
hexcal=$1
here=$(cd "$(dirname "$0")" && pwd)
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT

"$hexcal" export --robot inria-left-hand --format linuxcnc-hal --out "$dir/kins.hal" | grep -q "in mm (robot file in cm)"
"$hexcal" export --robot inria-left-hand --format linuxcnc-hal --machine-unit inch --out "$dir/inch.hal" >/dev/null
python3 - "$dir/kins.hal" "$dir/inch.hal" "$here/../../resources/robots/inria-left-hand.yaml" <<'PY'
import re, sys
def pins(path):
    return {m[1]: float(m[2]) for m in re.finditer(r"^setp (\S+) (\S+)$", open(path).read(), re.M)}
mm, inch = pins(sys.argv[1]), pins(sys.argv[2])
legs = re.findall(r"\{a: \[([^]]*)\], b: \[([^]]*)\], l: ([0-9.]+)", open(sys.argv[3]).read())
assert len(legs) == 6 and len(mm) == 37 and len(inch) == 37, (len(legs), len(mm), len(inch))
for n, (a, b, _) in enumerate(legs):
    for kind, point in (("base", a), ("platform", b)):
        for axis, value in zip("xyz", (float(v) for v in point.split(","))):
            pin = f"genhexkins.{kind}.{n}.{axis}"
            assert abs(mm[pin] - 10 * value) < 1e-9, (pin, mm[pin], value)
            assert abs(inch[pin] - value / 2.54) < 1e-9, (pin, inch[pin], value)
assert mm["genhexkins.spindle-offset"] == 0
PY
grep -q "^# leg 1: l = 522.496 mm" "$dir/kins.hal"

refused() {  # refused CODE PATTERN ARGS...
  local code=$1 pattern=$2 got=0
  shift 2
  "$hexcal" export "$@" >/dev/null 2>"$dir/err" || got=$?
  [ "$got" -eq "$code" ] || { echo "exit $got for $*"; cat "$dir/err"; exit 1; }
  grep -q -- "$pattern" "$dir/err" || { echo "no '$pattern' in: $(cat "$dir/err")"; exit 1; }
}
refused 2 "kins.hal: exists; use --force" --robot inria-left-hand --format linuxcnc-hal --out "$dir/kins.hal"
refused 2 "unknown format 'urdf'; accepted: linuxcnc-hal" --robot inria-left-hand --format urdf --out "$dir/x"
refused 2 "--machine-unit: 'cm' is not a LinuxCNC linear unit; accepted: mm, inch" \
  --robot inria-left-hand --format linuxcnc-hal --machine-unit cm --out "$dir/x"
refused 2 "no-such-robot" --robot no-such-robot --format linuxcnc-hal --out "$dir/x"
[ ! -e "$dir/x" ]
"$hexcal" export --robot inria-left-hand --format linuxcnc-hal --out "$dir/kins.hal" --force >/dev/null
echo "export: ok"
