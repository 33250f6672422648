#!/usr/bin/env bash
# Rotor 37 hold-out study (docs/benchmarks.md, "Spanwise accuracy"):
#  1. every second section withheld (loft 0,2,...,12; measure 1,3,...,11), for the span
#     parameterisations and degrees interlin offers;
#  2. leave-one-out: each interior section withheld alone from the full 13-section loft. Halving
#     the section spacing should shrink a smooth surface's error ~16x (cubic); where it does not,
#     the error is the data's own section-to-section irregularity, which no interpolating surface
#     can remove.
# Usage: bash studies/rotor37_holdout.sh [path/to/interlin]   (prints a Markdown table)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cli=${1:-$root/build/tools/interlin}
data=$root/data/rotor37/sections.csv
summary() { "$cli" loft "$data" -q "$@" | sed -n 's/.*withheld sections: max \([^,]*\), rms \(.*\)/\1 | \2/p'; }

echo "### Every second section withheld (7 lofted, 6 x 198 points measured)"
echo
echo "| span parameters | span degree | correspondence | max [cm] | rms [cm] |"
echo "|---|---|---|---|---|"
for sp in centripetal chord uniform; do
  for q in 3 5; do
    for m in index arclength; do
      echo "| $sp | $q | $m | $(summary --holdout 2 --span-param $sp --span-degree $q --match $m) |"
    done
  done
done
echo "| centripetal | 3 | arclength, start at LE (--align le) | $(summary --holdout 2 --align le) |"
echo "| centripetal | 1 (linear) | index | $(summary --holdout 2 --span-degree 1) |"
echo
echo "### Leave one out (12 lofted, 198 points measured)"
echo
echo "| withheld section | max [cm] | rms [cm] |"
echo "|---|---|---|"
for i in $(seq 1 11); do
  echo "| $i | $(summary --withhold "$i") |"
done
