#!/usr/bin/env bash
# camera_convert.sh HEXCAL DATA: `hexcal camera show` and `camera convert`
# through the real binary. The ROS and Kalibr files are read back with PyYAML,
# as ROS's and Kalibr's Python tools read them (YAML 1.1: a number without a
# '.' is an int, "1e-05" a string), and compared, value for value, with the
# camera they came from; then bad inputs, each with its exit code and message,
# and no file written or replaced. Exit 77 (skipped) only without PyYAML.
set -u
hexcal=$(realpath "$1") data=$(realpath "$2")
python=/usr/bin/python3
if ! "$python" -c 'import yaml' 2>/dev/null; then
  echo "skipped: PyYAML is not installed (Debian's python3-yaml; scripts/install-deps.sh installs it)"
  exit 77
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# expect CODE REGEX ARGS...: runs hexcal ARGS (20 s at most) and checks its exit code and output.
expect() {
  local code=$1 regex=$2 output rc
  shift 2
  output=$(timeout 20 "$hexcal" "$@" 2>&1)
  rc=$?
  if [ "$rc" -ne "$code" ]; then fail "exit code $rc, expected $code: hexcal $*"; echo "$output"; return; fi
  if ! grep -Eq -- "$regex" <<<"$output"; then
    fail "output does not match /$regex/: hexcal $*"; echo "$output"; return
  fi
  echo "ok: hexcal $*"
}

# check NAME PYTHON...: runs a PyYAML check (its arguments after the script).
check() {
  local name=$1
  shift
  if "$python" - "$@" >py.out 2>&1; then echo "ok: $name"; else fail "$name"; cat py.out; fi
}

# show: the model, the size, fx fy cx cy, the named coefficients, the field of view.
expect 0 "^camera sim-4.2mm-1024x768: radtan .*1024 x 768 px" camera show sim-4.2mm-1024x768
expect 0 "pinhole \(px\): fx 903.2 fy 903.2 cx 515.3 cy 380.1" camera show sim-4.2mm-1024x768
expect 0 "distortion: +k1 -0.28 k2 0.09 p1 0.0004 p2 -0.0003 k3 -0.012" camera show sim-4.2mm-1024x768
expect 0 "field of view: [0-9.]+ deg horizontal, [0-9.]+ deg vertical, [0-9.]+ deg diagonal" \
  camera show "$data/cameras/ros_camera_info.yaml"
"$hexcal" camera show "$data/cameras/kalibr_tumvi_camchain.yaml" --json >tumvi.json || fail "camera show --json"
check "show --json: one object, the TUM VI camera's numbers" tumvi.json \
  "$data/cameras/kalibr_tumvi_camchain.yaml" <<'PY'
import json, sys, yaml
shown = json.load(open(sys.argv[1]))
cam = yaml.safe_load(open(sys.argv[2]))["cam0"]
assert shown["model"] == "pinhole-equi", shown["model"]
assert [shown[k] for k in ("fx", "fy", "cx", "cy")] == cam["intrinsics"], shown
assert shown["coefficient_names"] == ["k1", "k2", "k3", "k4"], shown["coefficient_names"]
assert shown["coefficients"] == cam["distortion_coeffs"], shown["coefficients"]
assert [shown["width"], shown["height"]] == cam["resolution"]
fov = shown["field_of_view_deg"]
assert 150 < fov["horizontal"] < 160 and fov["diagonal"] > 180, fov  # its corners are past 90 deg off axis
PY

# ROS camera_info of the simulated camera (radtan, 5 coefficients).
expect 0 "wrote sim_ros.yaml: ros file of the radtan camera sim-4.2mm-1024x768 \(1024 x 768\)" \
  camera convert sim-4.2mm-1024x768 --to ros --out sim_ros.yaml --camera-name hexcal_sim
check "ros: camera_calibration_parsers' keys and values, floats" sim_ros.yaml <<'PY'
import sys, yaml
info = yaml.safe_load(open(sys.argv[1]))
assert list(info) == ["image_width", "image_height", "camera_name", "camera_matrix", "distortion_model",
                      "distortion_coefficients", "rectification_matrix", "projection_matrix"], list(info)
assert (info["image_width"], info["image_height"], info["camera_name"]) == (1024, 768, "hexcal_sim"), info
def matrix(key, rows, cols):
    m = info[key]
    assert (m["rows"], m["cols"]) == (rows, cols) and len(m["data"]) == rows * cols, (key, m)
    assert all(type(v) is float for v in m["data"]), (key, m["data"])
    return m["data"]
assert matrix("camera_matrix", 3, 3) == [903.2, 0, 515.3, 0, 903.2, 380.1, 0, 0, 1]
assert info["distortion_model"] == "plumb_bob"
assert matrix("distortion_coefficients", 1, 5) == [-0.28, 0.09, 0.0004, -0.0003, -0.012]
assert matrix("rectification_matrix", 3, 3) == [1, 0, 0, 0, 1, 0, 0, 0, 1]
assert matrix("projection_matrix", 3, 4) == [903.2, 0, 515.3, 0, 0, 903.2, 380.1, 0, 0, 0, 1, 0]
PY
# Kalibr's radtan has no k3: the simulated camera (k3 = -0.012) is refused, nothing written.
CANNOT="a Kalibr camchain cannot hold this camera"
expect 2 "sim_ros.yaml: $CANNOT: k3 = -0.012, and Kalibr's radtan has k1 k2 p1 p2 only" \
  camera convert sim_ros.yaml --to kalibr --out never.yaml
[ -e never.yaml ] && fail "a refused conversion wrote never.yaml"

# A Kalibr radtan camera (EuRoC's cam0, k3 = 0) and the TUM VI fisheye: to ROS
# and back to Kalibr; PyYAML reads the same numbers as in the file they came from.
cat >euroc.yaml <<'YAML'
cam0:
  camera_model: pinhole
  intrinsics: [458.654, 457.296, 367.215, 248.375]
  distortion_model: radtan
  distortion_coeffs: [-0.28340811, 0.07395907, 0.00019359, 1.76187114e-05]
  resolution: [752, 480]
  rostopic: /cam0/image_raw
YAML
for camera in euroc.yaml "$data/cameras/kalibr_tumvi_camchain.yaml"; do
  name=$(basename "$camera" .yaml)
  expect 0 "wrote ${name}_ros.yaml: ros file" camera convert "$camera" --to ros --out "${name}_ros.yaml"
  expect 0 "wrote ${name}_kalibr.yaml: kalibr file" camera convert "${name}_ros.yaml" --to kalibr \
    --out "${name}_kalibr.yaml"
  expect 0 "wrote ${name}_opencv.yaml: opencv file" camera convert "${name}_kalibr.yaml" --to opencv \
    --out "${name}_opencv.yaml"
  check "$name: kalibr -> ros -> kalibr keeps every number (PyYAML)" "$camera" "${name}_ros.yaml" \
    "${name}_kalibr.yaml" <<'PY'
import sys, yaml
original = yaml.safe_load(open(sys.argv[1]))["cam0"]
info = yaml.safe_load(open(sys.argv[2]))
chain = yaml.safe_load(open(sys.argv[3]))
assert list(chain) == ["cam0"], list(chain)
cam = chain["cam0"]
for key in ("camera_model", "intrinsics", "distortion_model", "distortion_coeffs", "resolution"):
    assert cam[key] == original[key], (key, cam[key], original[key])
# Kalibr's CameraParameters checks: floats for fu fv pu pv, ints for the resolution.
assert all(type(v) is float for v in cam["intrinsics"] + cam["distortion_coeffs"]), cam
assert all(type(v) is int for v in cam["resolution"]), cam
fu, fv, pu, pv = original["intrinsics"]
assert info["camera_matrix"]["data"] == [fu, 0, pu, 0, fv, pv, 0, 0, 1], info["camera_matrix"]
assert info["distortion_model"] == {"radtan": "plumb_bob", "equidistant": "equidistant"}[original["distortion_model"]]
d = info["distortion_coefficients"]["data"]
assert d == original["distortion_coeffs"] + ([0.0] if original["distortion_model"] == "radtan" else []), d
assert [info["image_width"], info["image_height"]] == original["resolution"]
PY
  if ! { "$hexcal" camera show "$camera" --json >a.json && "$hexcal" camera show "${name}_opencv.yaml" --json >b.json; }
  then
    fail "camera show $name"
  fi
  check "$name: the same camera after three conversions (hexcal's reading)" a.json b.json <<'PY'
import json, sys
a, b = (json.load(open(path)) for path in sys.argv[1:3])
del a["source"], b["source"]
assert a == b, (a, b)
PY
done

# The rational model: ROS has it (rational_polynomial, 8 coefficients); Kalibr does not.
cat >rational.yaml <<'YAML'
image_width: 640
image_height: 480
camera_matrix: {rows: 3, cols: 3, data: [500, 0, 320, 0, 501, 240, 0, 0, 1]}
distortion_model: rational_polynomial
distortion_coefficients: {rows: 1, cols: 8, data: [0.4, -0.1, 1e-05, -0.0003, 0.02, 0.68, 0.02, 0.01]}
YAML
expect 0 "wrote rational_ros.yaml" camera convert rational.yaml --to ros --out rational_ros.yaml
check "rational: ros rational_polynomial, 8 float coefficients" rational_ros.yaml <<'PY'
import sys, yaml
info = yaml.safe_load(open(sys.argv[1]))
assert info["distortion_model"] == "rational_polynomial", info["distortion_model"]
assert info["distortion_coefficients"]["data"] == [0.4, -0.1, 1e-05, -0.0003, 0.02, 0.68, 0.02, 0.01], info
assert info["camera_matrix"]["data"][0] == 500.0 and info["camera_name"] == "camera", info
PY
expect 2 "rational.yaml: $CANNOT: Kalibr has no rational model \(k1 k2 p1 p2 k3 k4 k5 k6\)" \
  camera convert rational.yaml --to kalibr \
  --out never.yaml
[ -e never.yaml ] && fail "a refused conversion wrote never.yaml"

# Bad inputs: exit 2 with the file or option named, nothing written.
mkdir folder
mkfifo fifo.yaml
printf 'old out\n' >out.yaml
expect 2 "missing.yaml: no such file" camera convert missing.yaml --to ros --out x.yaml
expect 2 "missing.yaml: no such file" camera show missing.yaml
expect 2 "folder: is a directory, not a file" camera convert folder --to ros --out x.yaml
expect 2 "fifo.yaml: not a regular file \(a FIFO\)" camera convert fifo.yaml --to ros --out x.yaml
expect 2 "fifo.yaml: not a regular file \(a FIFO\)" camera show fifo.yaml
expect 2 "--to: unknown format 'matlab'; accepted: opencv, ros, kalibr" camera convert rational.yaml --to matlab \
  --out x.yaml
expect 2 "--camera-name: 'left cam' is not a ROS camera name: letters, digits and '_' only" camera convert \
  rational.yaml --to ros \
  --out x.yaml --camera-name "left cam"
[ -e x.yaml ] && fail "a refused conversion wrote x.yaml"
expect 2 "out.yaml: exists; use --force to overwrite it" camera convert rational.yaml --to ros --out out.yaml
[ "$(cat out.yaml)" = "old out" ] || fail "out.yaml was replaced without --force"
# What is not a file is never replaced, --force or not.
expect 2 "fifo.yaml: not a regular file \(a FIFO\); hexcal replaces only files" camera convert rational.yaml \
  --to ros --out fifo.yaml --force
[ -p fifo.yaml ] || fail "the FIFO was replaced"
expect 2 "folder: is a directory, not a file" camera convert rational.yaml --to ros --out folder --force
ln -s /dev/null null.yaml
expect 2 "null.yaml: not a regular file \(a character device\)" camera convert rational.yaml --to ros \
  --out null.yaml --force
[ -L null.yaml ] || fail "the link to /dev/null was replaced"
expect 0 "wrote out.yaml: ros file" camera convert rational.yaml --to ros --out out.yaml --force
grep -q "^distortion_model: rational_polynomial$" out.yaml || fail "--force did not replace out.yaml"
leftovers=$(find . -name '.*.tmp.*')
[ -n "$leftovers" ] && fail "temporary files left behind: $leftovers"
[ "$failures" -eq 0 ] || { echo "$failures failure(s)"; exit 1; }
echo "camera_convert: ok"
