#!/usr/bin/env bash
# scripts/sanitize-ctest.sh BUILD_DIR JOBS — the unit tests under ASan + UBSan
# (`make sanitize`, docs/hardening.md).
#
# LeakSanitizer's stop-the-world tracer itself crashes now and then at process
# exit, after every test of the binary has passed ("Tracer caught signal 11 ...
# LeakSanitizer has encountered a fatal error"; google/sanitizers#1353). When
# that message is in the log, the failed tests are run once more; a leak, an
# ASan or UBSan report or a test failure is deterministic and fails again, and
# so does the tracer crash if it repeats.
set -uo pipefail
dir=$1 jobs=$2
log=$(mktemp)
trap 'rm -f "$log"' EXIT
# Label `sweep`: detection swept over every image and its variants (minutes at
# -O3; vision/library_floor_test), which the sanitizers would make ten times
# longer while the same code runs under them in vision/detection_test.
# Two cases of core/fk_homotopy_test sweep every corner of the strokes with
# many starts (3 of the binary's 4 minutes under the sanitizers); the same
# homotopy code runs under them in the binary's other cases.
export GTEST_FILTER='-FkFamily.SameModesAsTheGenericStart:ForwardKinematicsAll.InriaStrokeCorners'
# The folders here are HEXCAL_SANITIZED_FOLDERS (cmake/HexcalTesting.cmake), whose tests hexcal_unit_tests builds.
ctest --test-dir "$dir" -R '^(core|vision|charts|devices|session|sim|report|workflow)/' -LE sweep --output-on-failure -j"$jobs" 2>&1 | tee "$log"
status=${PIPESTATUS[0]}
if [ "$status" -eq 0 ] || ! grep -q "Tracer caught signal" "$log"; then exit "$status"; fi
echo "sanitize: LeakSanitizer's tracer crashed at exit (google/sanitizers#1353); running the failed tests once more"
ctest --test-dir "$dir" --rerun-failed --output-on-failure -j"$jobs"
