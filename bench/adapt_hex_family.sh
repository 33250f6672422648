#!/bin/bash
# interlin mesh --volume hex --adapt on the shipped models at cells and passes the tests do not
# use: one line per run with the smallest scaled Jacobian, inverted elements, volume, folded
# children untangled, held boundary nodes, and any error or undone pass (docs/benchmarks.md,
# "Children on sliver faces"). Usage: bench/adapt_hex_family.sh [INTERLIN] > family.txt
# (INTERLIN defaults to build/tools/interlin; run two builds and diff the outputs).
set -u
interlin=${1:-build/tools/interlin}
models=$(dirname "$0")/../data/models
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
run() {
  local model=$1
  shift
  local text
  text=$("$interlin" mesh "$models/$model.rf" -o "$out/m.vtu" --volume hex "$@" --threads 2 -q 2>&1)
  echo "$model $* | $(echo "$text" | grep -oE 'scaled Jacobian min [^ ]+|inverted [0-9]+|volume [0-9.]+|untangled [0-9 of]+|valid [0-9 ]+|undone: [0-9]+|interlin: [^(]*' | tr '\n' ';')"
}
for c in 0.25 0.3 0.35 0.45; do run car --cell $c --adapt 1; done
for c in 0.15 0.3; do run valve --cell $c --adapt 1; done
for c in 0.08 0.1; do run uav --cell $c --adapt 1; done
for c in 0.25 0.3 0.4; do run impeller --cell $c --adapt 1; done
for r in 16 32; do run body11 --resolution $r --adapt 1; done
run naca0011_plate --adapt 1
run naca0011_plate --resolution 24 --adapt 2
run valve --cell 0.4 --adapt 2
run valve --cell 0.5 --adapt 2
