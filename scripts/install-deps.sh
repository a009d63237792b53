#!/usr/bin/env bash
# Installs the Debian 12 (bookworm) packages hexcal builds and tests with.
# Idempotent: installs only what is missing. Needs root (or sudo) for apt-get.
set -euo pipefail

packages=(
  build-essential cmake ninja-build ccache pkg-config git
  libeigen3-dev libceres-dev libnlopt-cxx-dev
  libopencv-dev libopencv-contrib-dev libapriltag-dev
  qtbase5-dev libqt5charts5-dev libqt5svg5-dev
  libvtk9-dev libvtk9-qt-dev mpi-default-dev
  libyaml-cpp-dev nlohmann-json3-dev libcli11-dev
  # PyYAML: tests/cli/camera_convert.sh reads the ROS and Kalibr files as their Python tools do.
  python3-yaml
  libgtest-dev libgmock-dev libbenchmark-dev
  xvfb xauth libgl1-mesa-dri
  clang libclang-rt-14-dev
  # LinuxCNC (2.9, Debian's build without a realtime kernel): the simulated
  # hexapod of scripts/linuxcnc-sim.sh and tests/cli/linuxcnc.sh; ~40 s.
  linuxcnc-uspace
  # GenICam cameras through Aravis 0.8 (the aravis:NAME camera, the fake GigE
  # Vision camera of the tests, arv-tool-0.8 and arv-fake-gv-camera-0.8).
  # libusb-1.0-0-dev: aravis-0.8.pc requires it, and --no-install-recommends
  # leaves it out (../shared/devices.md).
  aravis-tools aravis-tools-cli libaravis-dev libusb-1.0-0-dev
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

echo "install-deps: installing ${#missing[@]} missing packages: ${missing[*]}"
sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "install-deps: need root or sudo to run apt-get" >&2; exit 1; }
  sudo_cmd=(sudo)
fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
echo "install-deps: done"
