#!/usr/bin/env bash
# linuxcnc-sim.sh start DIR --robot ROBOT --home "X Y Z Q1 Q2 Q3" [--port PORT] [--hexcal BIN]
# linuxcnc-sim.sh camera DIR --session SESSION [--seed N] [--hexcal BIN]
# linuxcnc-sim.sh stop DIR
# linuxcnc-sim.sh env DIR     (prints the RTAPI_UID and RTAPI_FIFO_PATH halcmd needs, as `export` lines)
#
# A headless simulated LinuxCNC hexapod with a robot file's geometry, for
# trying `hexcal acquire --controller linuxcnc://127.0.0.1:PORT` without a
# machine (docs/acquisition.md). `start` writes DIR/machine.ini and
# DIR/genhexkins.hal (from `hexcal export --format linuxcnc-hal`), DIR/robot.yaml
# (the robot file the machine runs with) and starts
# LinuxCNC with linuxcncrsh on PORT (default 5007; it listens on every
# interface); `stop` shuts it down through linuxcncrsh and waits for it.
# `camera` starts `hexcal sim-camera` for the machine of DIR (a GigE Vision
# camera on 127.0.0.1 showing where SESSION's hidden true robot puts the
# machine's joints), prints its URL (aravis:...) and keeps it in DIR/camera;
# `stop` stops it too.
#
# The machine works in mm ([TRAJ] LINEAR_UNITS = mm), whatever the robot's
# unit. Its joints are the full leg lengths: joint limits are the strokes plus
# the offsets l, widened by 2 % of the stroke, and the joints home at the exact IK of --home (robot unit,
# degrees, the robot's Euler convention; angles 0 for a zyx robot), so that
# homing leaves no residual pose. As root, rtapi_app needs RTAPI_UID and a
# FIFO folder it can write (../shared/devices.md): both are set here.
# One LinuxCNC runs per host (its shared memory has fixed keys).
set -euo pipefail

usage() {
  echo "usage: $0 start DIR --robot ROBOT --home \"X Y Z Q1 Q2 Q3\" [--port PORT] [--hexcal BIN]" \
       "| camera DIR --session SESSION [--seed N] [--hexcal BIN] | stop DIR | env DIR" >&2
  exit 2
}
die() { echo "linuxcnc-sim: $*" >&2; exit 1; }

[ $# -ge 2 ] || usage
action=$1 dir=$2
shift 2

port_open() { (exec 3<>"/dev/tcp/127.0.0.1/$1") 2>/dev/null; }

# The INI, from the robot's JSON form, the IK of the home pose and the port.
write_ini() {  # write_ini ROBOT_JSON IK_JSON HOME PORT > machine.ini
  python3 - "$@" <<'EOF'
import json, sys
robot, ik = json.loads(sys.argv[1]), json.loads(sys.argv[2])
home, port = [float(v) for v in sys.argv[3].split()], int(sys.argv[4])
mm = {"mm": 1.0, "cm": 10.0, "m": 1000.0}[robot["length_unit"]]
if robot["euler"] != "xyz" and any(home[3:]):
    sys.exit("linuxcnc-sim: --home angles must be 0 for a zyx robot (TRAJ HOME is in genhexkins' A B C)")
legs, readings = robot["legs"], ik["poses"][0]["legs"]
if not ik["poses"][0]["feasible"]:
    sys.exit("linuxcnc-sim: --home is out of the robot's workspace: " + ik["poses"][0]["worst_constraint"])
out = [f"""# Written by scripts/linuxcnc-sim.sh for robot '{robot["name"]}' (lengths in mm).
[EMC]
VERSION = 1.1
MACHINE = hexcal-sim {robot["name"]}
[DISPLAY]
DISPLAY = linuxcncrsh -p {port}
[TASK]
TASK = milltask
CYCLE_TIME = 0.010
[RS274NGC]
PARAMETER_FILE = sim.var
[EMCMOT]
EMCMOT = motmod
COMM_TIMEOUT = 1.0
SERVO_PERIOD = 1000000
[EMCIO]
EMCIO = io
CYCLE_TIME = 0.100
TOOL_TABLE = sim.tbl
[HAL]
HALFILE = LIB:basic_sim.tcl -no_use_hal_manualtoolchange -no_sim_spindle
HALFILE = genhexkins.hal
[TRAJ]
COORDINATES = X Y Z A B C
LINEAR_UNITS = mm
ANGULAR_UNITS = degree
HOME = {" ".join(f"{v * mm:.9f}" for v in home[:3])} {" ".join(f"{v:.9f}" for v in home[3:])}
MAX_LINEAR_VELOCITY = 200
MAX_ANGULAR_VELOCITY = 100
[KINS]
KINEMATICS = genhexkins
JOINTS = 6
"""]
for j, (leg, reading) in enumerate(zip(legs, readings)):
    joint = (reading + leg["l"]) * mm
    # End stops 2 % of the stroke outside it: the planner keeps poses within the
    # strokes, but a G0 between two poses moves in world space and a leg can
    # pass its end points on the way (a pose at a stroke end then trips the limit).
    margin = 0.02 * (leg["stroke"][1] - leg["stroke"][0])
    low, high = ((s + leg["l"]) * mm for s in (leg["stroke"][0] - margin, leg["stroke"][1] + margin))
    out.append(f"""[JOINT_{j}]
TYPE = LINEAR
HOME = {joint:.9f}
HOME_OFFSET = {joint:.9f}
HOME_SEQUENCE = 0
MIN_LIMIT = {low:.9f}
MAX_LIMIT = {high:.9f}
MAX_VELOCITY = 200
MAX_ACCELERATION = 2000
""")
for axis in "XYZABC":
    out.append(f"[AXIS_{axis}]\nMIN_LIMIT = -100000\nMAX_LIMIT = 100000\nMAX_VELOCITY = 200\nMAX_ACCELERATION = 2000\n")
print("".join(out), end="")
EOF
}

start() {
  local robot="" home="" port=5007 hexcal=hexcal
  while [ $# -gt 0 ]; do
    case $1 in
      --robot) robot=$2; shift 2 ;;
      --home) home=$2; shift 2 ;;
      --port) port=$2; shift 2 ;;
      --hexcal) hexcal=$2; shift 2 ;;
      *) usage ;;
    esac
  done
  [ -n "$robot" ] && [ -n "$home" ] || usage
  command -v linuxcnc >/dev/null || die "linuxcnc is not installed (Debian 12: apt-get install linuxcnc-uspace)"
  ! port_open "$port" || die "port $port is in use"
  if pid=$(pgrep -x rtapi_app); then die "another LinuxCNC runs on this host (rtapi_app $pid): one at a time"; fi
  mkdir -p "$dir"
  dir=$(cd "$dir" && pwd)
  chmod 755 "$dir"  # rtapi_app runs as RTAPI_UID and reads below it
  [ ! -e "$dir/linuxcnc.pid" ] || die "$dir: a machine was started there and not stopped (linuxcnc-sim.sh stop $dir)"
  "$hexcal" export --robot "$robot" --format linuxcnc-hal --machine-unit mm --out "$dir/genhexkins.hal" --force >/dev/null
  # The robot the machine runs with (its offsets l are the joint homes), for `hexcal sim-camera --machine-robot`.
  "$hexcal" export --robot "$robot" --format robot --out "$dir/robot.yaml" --force >/dev/null
  echo "x,y,z,q1,q2,q3" >"$dir/home.csv"
  echo "$home" | tr ' ' ',' >>"$dir/home.csv"
  write_ini "$("$hexcal" robot show "$robot" --json)" "$("$hexcal" ik --robot "$robot" --poses "$dir/home.csv" --json)" \
    "$home" "$port" >"$dir/machine.ini.tmp"
  mv "$dir/machine.ini.tmp" "$dir/machine.ini"
  : >"$dir/sim.tbl"
  local fifo
  fifo=$(mktemp -d /tmp/hexcal-rtapi.XXXXXX)
  chmod 1777 "$fifo"
  echo "$fifo" >"$dir/rtapi_dir"
  echo "$port" >"$dir/port"
  # setsid execs linuxcnc (no fork): $! is LinuxCNC's pid and its process group.
  (cd "$dir"
   RTAPI_UID=65534 RTAPI_FIFO_PATH="$fifo/rtapi_fifo" setsid linuxcnc -r machine.ini >linuxcnc.log 2>&1 </dev/null &
   echo $! >linuxcnc.pid)
  local pid
  pid=$(cat "$dir/linuxcnc.pid")
  for _ in $(seq 300); do
    port_open "$port" && { echo "linuxcnc-sim: LinuxCNC (pid $pid) serves linuxcncrsh on port $port"; return 0; }
    kill -0 "$pid" 2>/dev/null || break
    sleep 0.1
  done
  tail -n 20 "$dir/linuxcnc.log" >&2
  stop
  die "LinuxCNC did not open port $port within 30 s (its log is above and in $dir/linuxcnc.log)"
}

# hexcal sim-camera in its own session, its URL read from its first line.
camera() {
  local session="" seed=1 hexcal=hexcal
  while [ $# -gt 0 ]; do
    case $1 in
      --session) session=$2; shift 2 ;;
      --seed) seed=$2; shift 2 ;;
      --hexcal) hexcal=$2; shift 2 ;;
      *) usage ;;
    esac
  done
  [ -n "$session" ] || usage
  [ -e "$dir/robot.yaml" ] || die "$dir: no machine started there (linuxcnc-sim.sh start $dir ...)"
  [ ! -e "$dir/camera.pid" ] || die "$dir: a camera was started there and not stopped"
  setsid "$hexcal" sim-camera --session "$session" --machine-robot "$dir/robot.yaml" --seed "$seed" \
    >"$dir/camera.log" 2>&1 </dev/null &
  echo $! >"$dir/camera.pid"
  for _ in $(seq 100); do
    local url
    url=$(sed -n 's/^sim-camera: serving \(aravis:.*\) on [0-9.]*, following .*/\1/p' "$dir/camera.log")
    if [ -n "$url" ]; then echo "$url" >"$dir/camera"; echo "$url"; return 0; fi
    kill -0 "$(cat "$dir/camera.pid")" 2>/dev/null || break
    sleep 0.1
  done
  cat "$dir/camera.log" >&2
  stop_camera
  die "hexcal sim-camera did not start within 10 s (its log is above)"
}

stop_camera() {
  [ -e "$dir/camera.pid" ] || return 0
  local pid
  pid=$(cat "$dir/camera.pid")
  kill -TERM "$pid" 2>/dev/null || true
  for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
  kill -KILL "$pid" 2>/dev/null || true
  rm -f "$dir/camera.pid" "$dir/camera"
}

stop() {
  stop_camera
  [ -e "$dir/linuxcnc.pid" ] || die "$dir: no machine started there"
  local pid port
  pid=$(cat "$dir/linuxcnc.pid")
  port=$(cat "$dir/port")
  # linuxcncrsh's shutdown ends LinuxCNC whole (rtapi_app and shared memory included).
  if port_open "$port"; then
    (exec 3<>"/dev/tcp/127.0.0.1/$port"
     printf 'hello EMC linuxcnc-sim 1.0\r\nset enable EMCTOO\r\nshutdown\r\n' >&3
     timeout 5 cat <&3 >/dev/null || true) 2>/dev/null || true
  fi
  for _ in $(seq 200); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
  if kill -0 "$pid" 2>/dev/null; then  # its own session (setsid): the group is what we started
    kill -TERM -- "-$pid" 2>/dev/null || true
    sleep 2
    kill -KILL -- "-$pid" 2>/dev/null || true
  fi
  rm -rf "$(cat "$dir/rtapi_dir")"
  rm -f "$dir/linuxcnc.pid" "$dir/port" "$dir/rtapi_dir"
  echo "linuxcnc-sim: stopped"
}

# What halcmd needs to reach this machine's HAL as root (../shared/devices.md).
print_env() {
  [ -e "$dir/rtapi_dir" ] || die "$dir: no machine running there"
  echo "export RTAPI_UID=65534 RTAPI_FIFO_PATH=$(cat "$dir/rtapi_dir")/rtapi_fifo"
}

case $action in
  start) start "$@" ;;
  camera) camera "$@" ;;
  stop) [ $# -eq 0 ] || usage; stop ;;
  env) [ $# -eq 0 ] || usage; print_env ;;
  *) usage ;;
esac
