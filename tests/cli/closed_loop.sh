#!/usr/bin/env bash
# closed_loop.sh HEXCAL: the acquisition loop with real device software, in
# simulation (docs/acquisition.md, "The closed loop in simulation"): LinuxCNC
# (scripts/linuxcnc-sim.sh) runs inria-left-hand's nominal geometry; `hexcal
# sim-camera` serves, as a GigE Vision camera through libaravis, the board
# where a hidden true robot puts LinuxCNC's joints; `hexcal acquire` drives
# the machine through a 16-pose plan and grabs each frame with the `aravis:`
# camera; `calibrate --session` must then beat the nominal robot against the
# hidden truth (truth_error.py). Skipped (77) without LinuxCNC, without
# Aravis in this build, or when another LinuxCNC runs on the host.
set -eu
hexcal=$1
here=$(cd "$(dirname "$0")" && pwd)
sim=$here/../../scripts/linuxcnc-sim.sh
command -v linuxcnc >/dev/null || { echo "linuxcnc is not installed: skipped"; exit 77; }
if pid=$(pgrep -x rtapi_app); then echo "another LinuxCNC runs on this host (rtapi_app $pid): skipped"; exit 77; fi
if "$hexcal" sim-camera --session /nonexistent --follow linuxcnc://127.0.0.1:1 --machine-robot x 2>&1 |
  grep -q "built without Aravis"; then echo "hexcal was built without Aravis: skipped"; exit 77; fi
dir=$(mktemp -d)
camera_pid=
cleanup() {
  [ -z "$camera_pid" ] || { kill "$camera_pid" 2>/dev/null || true; wait "$camera_pid" 2>/dev/null || true; }
  [ ! -e "$dir/machine/linuxcnc.pid" ] || "$sim" stop "$dir/machine" >/dev/null || true
  rm -rf "$dir"
}
trap cleanup EXIT
port=$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
s=$dir/s
"$hexcal" session init --robot inria-left-hand --camera sim-4.2mm-1024x768 --target aprilgrid-6x6 \
  --noise-position 0.005 --noise-angle 0.02 --noise-leg 0.001 "$s" >/dev/null
"$hexcal" plan --robot inria-left-hand --poses 16 --candidate-count 400 --seed 3 --no-certificate \
  --out "$s/plan.csv" >/dev/null

start=$(date +%s.%N)
"$sim" start "$dir/machine" --robot inria-left-hand --home "0 0 53.5 0 0 0" --port "$port" --hexcal "$hexcal" >/dev/null
"$hexcal" sim-camera --session "$s" --follow "linuxcnc://127.0.0.1:$port" --machine-robot "$dir/machine/robot.yaml" \
  --seed 2 --serial HEXCALCI >"$dir/camera.out" 2>"$dir/camera.err" &
camera_pid=$!
for _ in $(seq 100); do grep -q "serving aravis:" "$dir/camera.out" && break; sleep 0.1; done
camera=$(sed -n "s/^sim-camera: serving \(aravis:.*\) on [0-9.]*, following .*/\1/p" "$dir/camera.out")
[ -n "$camera" ] || { echo "sim-camera did not start:"; cat "$dir/camera.out" "$dir/camera.err"; exit 1; }

"$hexcal" acquire --session "$s" --controller "linuxcnc://127.0.0.1:$port" --camera "$camera" --settle 0.3 \
  --holdout-every 4 --json >"$dir/acquire.json" 2>"$dir/acquire.err" || { cat "$dir/acquire.err"; exit 1; }
end=$(date +%s.%N)
python3 - "$dir/acquire.json" "$start" "$end" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
assert r["recorded"] == 16 and r["failed"] == 0, r
print("closed loop: 16 poses through LinuxCNC and the aravis camera in %.1f s (machine start included)" %
      (float(sys.argv[3]) - float(sys.argv[2])))
PY
"$hexcal" calibrate --session "$s" --json >"$dir/report.json" 2>"$dir/calibrate.err" ||
  { cat "$dir/calibrate.err"; exit 1; }
python3 "$here/truth_error.py" "$s" "$here/../../resources/robots/inria-left-hand.yaml" "$dir/report.json"
echo "closed loop: ok"
