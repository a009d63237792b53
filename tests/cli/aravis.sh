#!/usr/bin/env bash
# aravis.sh HEXCAL: `hexcal acquire --camera aravis:NAME` against Aravis' own
# GigE Vision simulator (arv-fake-gv-camera-0.8, 512x512 Mono8 at 25 fps) on
# 127.0.0.1: three poses recorded at the camera's size, exposure and gain from
# the URL, a missing camera listing the cameras Aravis sees, an exposure out
# of the camera's range refused (docs/acquisition.md). Skipped (exit 77)
# without Aravis' tools, in a build without Aravis, or while another GigE
# Vision camera serves 127.0.0.1 (one per address).
set -eu
hexcal=$1
if ! command -v arv-fake-gv-camera-0.8 >/dev/null; then
  echo "arv-fake-gv-camera-0.8 is not installed (scripts/install-deps.sh): skipped"; exit 77
fi
dir=$(mktemp -d)
fake_pid=
cleanup() {
  [ -z "$fake_pid" ] || kill "$fake_pid" 2>/dev/null || true
  rm -rf "$dir"
}
trap cleanup EXIT
s=$dir/s
"$hexcal" session init --robot inria-left-hand --camera sim-4.2mm-1024x768 --target aprilgrid-6x6 "$s" >/dev/null
cp "$(dirname "$0")/../data/poses/acquire_three.csv" "$dir/poses.csv"
acquire() {  # acquire CAMERA: exit code in $code, stdout in $dir/out, stderr in $dir/err
  code=0
  "$hexcal" acquire --session "$s" --controller sim --camera "$1" --poses "$dir/poses.csv" \
    >"$dir/out" 2>"$dir/err" || code=$?
}
acquire "aravis:Cam?exposure=fast"
if grep -q "built without Aravis" "$dir/err"; then echo "hexcal was built without Aravis: skipped"; exit 77; fi
if ! python3 -c 'import socket; socket.socket(socket.AF_INET, socket.SOCK_DGRAM).bind(("127.0.0.1", 3956))' 2>/dev/null; then
  echo "another GigE Vision camera serves 127.0.0.1 (UDP 3956 in use): skipped"; exit 77
fi

arv-fake-gv-camera-0.8 -i 127.0.0.1 -s HEXCALCLI >"$dir/fake.log" 2>&1 &
fake_pid=$!
sleep 0.3
acquire "aravis:Aravis-Fake-HEXCALCLI?exposure=8000&gain=2"
[ "$code" -eq 0 ] || { echo "exit $code"; cat "$dir/out" "$dir/err"; exit 1; }
grep -q "3 recorded, 0 already recorded, 0 failed" "$dir/out" || { cat "$dir/out"; exit 1; }
grep -q "(Aravis Fake HEXCALCLI, 512x512 Mono8)" "$dir/out" || { cat "$dir/out"; exit 1; }
for k in 0 1 2; do
  size=$(python3 -c 'import struct, sys; d = open(sys.argv[1], "rb").read(24); print("%dx%d" % struct.unpack(">II", d[16:24]))' \
    "$s/images/pose_000$k.png")
  [ "$size" = 512x512 ] || { echo "pose_000$k.png is $size"; exit 1; }
done

acquire "aravis:No-Such-Camera"
[ "$code" -eq 2 ] || { echo "exit $code for a missing camera"; cat "$dir/err"; exit 1; }
grep -q "camera 'aravis:No-Such-Camera': no GenICam camera 'No-Such-Camera'; Aravis sees: .*Aravis-Fake-HEXCALCLI (127.0.0.1)" \
  "$dir/err" || { cat "$dir/err"; exit 1; }
acquire "aravis:Aravis-Fake-HEXCALCLI?exposure=1e9"
[ "$code" -eq 2 ] || { echo "exit $code for an exposure out of range"; cat "$dir/err"; exit 1; }
grep -q "exposure 1e+09 µs is outside the camera's range \[10, 1e+07\] µs" "$dir/err" || { cat "$dir/err"; exit 1; }
echo "aravis: 3 poses from arv-fake-gv-camera-0.8, a missing camera and a bad exposure refused"
