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
# --push needs the machine's files and address; refused, it writes nothing.
refused 2 "--push needs --running-robot" --robot inria-left-hand --out "$dir/x" --push --yes
refused 2 "--push needs --ini" --robot inria-left-hand --out "$dir/x" --push --yes --running-robot inria-left-hand
refused 2 "--push needs --format linuxcnc-hal" --robot inria-left-hand --format robot --out "$dir/x" --push
[ ! -e "$dir/x" ]
# A robot scaled out of any machine's size, or with a value that is not
# finite, is refused (1e70 was written as truncated digits, 1e-12 as zeros).
"$hexcal" export --robot inria-left-hand --format robot --out "$dir/robot.yaml" >/dev/null
scaled() {  # scaled FACTOR OUT: the robot's legs (a, b, l, stroke) times FACTOR, without its limits
  python3 - "$dir/robot.yaml" "$@" <<'PY'
import re, sys
text, factor = open(sys.argv[1]).read().split("limits:")[0], float(sys.argv[2])
scale = lambda m: repr(float(m.group(0)) * factor)
open(sys.argv[3], "w").write("\n".join(re.sub(r"-?\d+(\.\d+)?", scale, line) if line.lstrip().startswith("- {")
                                      else line for line in text.split("\n")))
PY
}
scaled 1e70 "$dir/huge.yaml"
refused 2 "is 1.33e+69 m from its frame's origin, outside \[0.001, 100\] m: is its length_unit right?" \
  --robot "$dir/huge.yaml" --out "$dir/x"
scaled 1e-12 "$dir/tiny.yaml"
refused 2 "is its length_unit right?" --robot "$dir/tiny.yaml" --out "$dir/x"
[ ! -e "$dir/x" ]
# A name with a line break stays in its comment: every line of the HAL file
# is a comment, a setp or blank (a `loadusr` line would run a program).
sed 's/^name: .*/name: "evil\\nloadusr \/bin\/sh -c reboot"/' "$dir/robot.yaml" >"$dir/evil.yaml"
"$hexcal" export --robot "$dir/evil.yaml" --out "$dir/evil.hal" >/dev/null
if grep -Ev '^(#.*|setp .*|)$' "$dir/evil.hal"; then echo "a HAL line that is not a comment or a setp"; exit 1; fi
grep -qF "robot 'evil\\x0aloadusr /bin/sh -c reboot'" "$dir/evil.hal"
"$hexcal" export --robot inria-left-hand --format linuxcnc-hal --out "$dir/kins.hal" --force >/dev/null
echo "export: ok"
