# Sourced by the CLI tests that run a simulated LinuxCNC (linuxcnc.sh,
# closed_loop.sh) after `hexcal=...`: skips (exit 77) without LinuxCNC or
# while another LinuxCNC runs on this host (one per host), and sets
#   sim   scripts/linuxcnc-sim.sh
#   dir   a temporary folder, removed at exit with its machine (and camera) stopped
#   port  a free TCP port on 127.0.0.1 for linuxcncrsh
sim=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/../../scripts/linuxcnc-sim.sh
if ! command -v linuxcnc >/dev/null; then
  echo "linuxcnc is not installed (apt-get install linuxcnc-uspace): skipped"; exit 77
fi
if pid=$(pgrep -x rtapi_app); then
  echo "another LinuxCNC runs on this host (rtapi_app $pid): skipped"; exit 77
fi
dir=$(mktemp -d)
cleanup() {
  [ ! -e "$dir/machine/linuxcnc.pid" ] || "$sim" stop "$dir/machine" >/dev/null || true
  rm -rf "$dir"
}
trap cleanup EXIT
port=$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
