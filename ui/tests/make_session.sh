#!/usr/bin/env bash
# make_session.sh HEXCAL OUT: the GUI tests' sessions, from `hexcal demo` (a
# virtual robot and camera; docs/session.md): 12 planned and 4 held-out images.
#   OUT/calibrated/ the demo session: planned, measured, calibrated
#   OUT/rendered/   its 16 images, not yet in a session (the flow test loads them)
#   OUT/session/    session.yaml and legs.csv of the same run, images/ empty
set -eu
hexcal=$1 out=$2
rm -rf "$out"
mkdir -p "$out"
"$hexcal" demo --poses 12 --holdout 4 --seed 2 --out "$out/calibrated" >/dev/null
cp -r "$out/calibrated/images" "$out/rendered"
s=$out/session
"$hexcal" session init --robot inria-left-hand --camera sim-4.2mm-1024x768 --target aprilgrid-6x6 \
  --noise-position 0.005 --noise-angle 0.02 --noise-leg 0.001 "$s" >/dev/null
cp "$out/calibrated/legs.csv" "$s/legs.csv"
