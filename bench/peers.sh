#!/usr/bin/env bash
# bench/peers.sh HEXCAL PEERS_DIR [RLIB] — hexcal against its peers in one run
# (docs/performance.md, "Against the peers"): the two programs alternated five
# times each, the medians and their ratio (hexcal / peer; below 1 is faster).
#   fk:   `hexcal fk --all` on Dietmaier's platform against PHCpack's `phc -b`
#         on the same system (PEERS_DIR/dietmaier-40-real.phc), per process.
#   plan: `hexcal plan` with its defaults on 10^5 random + boundary candidates
#         of the INRIA robot (the whole process) against R AlgDesign's
#         optFederov(~ . - 1, nTrials = 18, nRepeats = 1) on leg 1's
#         7-parameter rows of the same candidates (the call alone, rows given);
#         planO1: the same plan on O1 without polish or certificates.
# Needs phcpack, R and AlgDesign in RLIB (default /opt/rlib):
#   apt-get install phcpack r-base-dev
#   R CMD INSTALL -l /opt/rlib PEERS_DIR/AlgDesign_1.2.1.2.tar.gz
set -eu
hexcal=$1 peers=$2 rlib=${3:-/opt/rlib}
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
here=$(cd "$(dirname "$0")/.." && pwd)
median() { sort -g | awk 'NF { v[++n] = $1 } END { print v[int((n + 1) / 2)] }'; }
seconds() { local t0 t1; t0=$(date +%s.%N); "$@" >/dev/null 2>&1; t1=$(date +%s.%N); echo "$t1 - $t0" | bc -l; }
report() {  # report NAME HEXCAL_TIMES PEER_TIMES
  local h p
  h=$(tr ' ' '\n' <<<"$2" | median) p=$(tr ' ' '\n' <<<"$3" | median)
  printf '%-6s hexcal %8.3f s   peer %8.3f s   ratio %.4f\n' "$1" "$h" "$p" "$(echo "$h / $p" | bc -l)"
}

# fk --all against phc -b.
head -8 "$peers/dietmaier-40-real.phc" >"$dir/dietmaier.phc"  # the system, without phc's solutions
legs=1,0.645275,1.086284,1.503439,1.281933,0.771071
fk_h="" fk_p=""
for run in 1 2 3 4 5; do
  fk_h+=" $(seconds "$hexcal" fk --robot "$here/tests/data/dietmaier-40-real.yaml" --legs $legs --all --json)"
  rm -f "$dir/phc.out"
  fk_p+=" $(seconds phc -b "$dir/dietmaier.phc" "$dir/phc.out")"
done
real=$(grep -c "real regular" "$dir/phc.out")
modes=$("$hexcal" fk --robot "$here/tests/data/dietmaier-40-real.yaml" --legs $legs --all --json |
  python3 -c 'import json, sys; print(json.load(sys.stdin)["real_modes"])')
echo "fk: phc finds $real real regular solutions, hexcal $modes real modes"
report fk "$fk_h" "$fk_p"

# plan against optFederov.
"$hexcal" candidates --robot inria-left-hand --kind random --count 100000 --seed 1 --out "$dir/random.csv" >/dev/null
"$hexcal" candidates --robot inria-left-hand --kind boundary --out "$dir/boundary.csv" >/dev/null
{ cat "$dir/random.csv"; tail -n +2 "$dir/boundary.csv"; } >"$dir/candidates.csv"
cat >"$dir/federov.R" <<'R'
suppressMessages(library(AlgDesign, lib.loc = commandArgs(TRUE)[2]))
p <- read.csv(commandArgs(TRUE)[1])
# Leg 1 of the INRIA robot (resources/robots/inria-left-hand.yaml): eq. 5's row
# [-2v, 2 R^T v, -2|v|], v = P + R b - a, R = Rz(q3) Ry(q2) Rx(q1).
a <- c(-9.7, 9.1, 0); b <- c(-3, 7.3, 0)
rows <- t(apply(p, 1, function(x) {
  q <- x[4:6] * pi / 180
  rx <- matrix(c(1, 0, 0, 0, cos(q[1]), sin(q[1]), 0, -sin(q[1]), cos(q[1])), 3)
  ry <- matrix(c(cos(q[2]), 0, -sin(q[2]), 0, 1, 0, sin(q[2]), 0, cos(q[2])), 3)
  rz <- matrix(c(cos(q[3]), sin(q[3]), 0, -sin(q[3]), cos(q[3]), 0, 0, 0, 1), 3)
  r <- rz %*% ry %*% rx
  v <- x[1:3] + r %*% b - a
  c(-2 * v, 2 * t(r) %*% v, -2 * sqrt(sum(v^2)))
}))
rows <- data.frame(rows)
set.seed(1)
cat(system.time(optFederov(~ . - 1, rows, nTrials = 18, nRepeats = 1))[["elapsed"]], "\n")
R
plan_h="" o1_h="" plan_p=""
for run in 1 2 3 4 5; do
  plan_h+=" $(seconds "$hexcal" plan --robot inria-left-hand --poses 18 --candidates "$dir/candidates.csv" \
    --out "$dir/plan.csv" --force)"
  # The search alone, as the paper's IOOPS: O1, no polish, no certificates.
  o1_h+=" $(seconds "$hexcal" plan --robot inria-left-hand --poses 18 --candidates "$dir/candidates.csv" \
    --criterion O1 --polish 0 --no-certificate --out "$dir/plan.csv" --force)"
  plan_p+=" $(Rscript "$dir/federov.R" "$dir/candidates.csv" "$rlib" 2>/dev/null)"
done
report plan "$plan_h" "$plan_p"
report planO1 "$o1_h" "$plan_p"
