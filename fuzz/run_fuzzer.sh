#!/usr/bin/env bash
# run_fuzzer.sh FUZZER SEEDS SECONDS WORK: the bounded CTest run of one fuzz
# target (docs/hardening.md). New inputs go to WORK/corpus, the seed folder is
# only read; a crash, leak, sanitizer report or timeout is written to WORK/ as
# crash-*, leak-*, timeout-* ... and fails the test.
set -euo pipefail
fuzzer=$1 seeds=$2 seconds=$3 work=$4
rm -rf "$work"
mkdir -p "$work/corpus"
# -timeout: one input taking 10 s is a hang; -rss_limit_mb: an input that
# makes the parser allocate 2 GB is a bug too.
exec "$fuzzer" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
  -artifact_prefix="$work/" "$work/corpus" "$seeds"
