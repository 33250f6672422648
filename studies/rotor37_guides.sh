#!/usr/bin/env bash
# Rotor 37 hold-out with guide lines (docs/benchmarks.md, "Sections plus edge lines"):
# every second section withheld (loft 0,2,...,12; measure 1,3,...,11), sections only vs sections
# plus the leading- and trailing-edge lines taken from ALL 13 sections' edge points (the case
# where the designer knows the edge lines): LE = point 0 (J = 1), TE = point 99 (J = 100) of
# every section in data/rotor37/sections.csv. Also leave-one-out with and without the guides.
# Usage: bash studies/rotor37_guides.sh [path/to/interlin]   (prints Markdown tables, ~10 s)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cli=${1:-$root/build/tools/interlin}
data=$root/data/rotor37/sections.csv
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# Guide files: both edges, and each edge alone.
awk -F, 'NR == 1 { next }
         $2 == 0  { le = le "LE," $1 "," $3 "," $4 "," $5 "\n" }
         $2 == 99 { te = te "TE," $1 "," $3 "," $4 "," $5 "\n" }
         END { printf "guide,index,x,y,z\n%s%s", le, te > "'"$tmp"'/edges.csv";
               printf "guide,index,x,y,z\n%s", le > "'"$tmp"'/le.csv";
               printf "guide,index,x,y,z\n%s", te > "'"$tmp"'/te.csv" }' "$data"
summary() { "$cli" loft "$data" -q "$@" | sed -n 's/.*withheld sections: max \([^,]*\), rms \(.*\)/\1 | \2/p'; }

echo "### Every second section withheld (7 lofted, 6 x 198 points measured)"
echo
echo "| surface | span degree | max [cm] | rms [cm] |"
echo "|---|---|---|---|"
for q in 3 5; do
  echo "| sections only (foundation loft) | $q | $(summary --holdout 2 --span-degree $q) |"
  echo "| sections + LE guide | $q | $(summary --holdout 2 --span-degree $q --guides "$tmp/le.csv") |"
  echo "| sections + TE guide | $q | $(summary --holdout 2 --span-degree $q --guides "$tmp/te.csv") |"
  echo "| sections + LE and TE guides | $q | $(summary --holdout 2 --span-degree $q --guides "$tmp/edges.csv") |"
done
echo
echo "### Per withheld section (span degree 3)"
echo
echo "| withheld section | sections only max / rms [cm] | + LE and TE guides max / rms [cm] |"
echo "|---|---|---|"
per() { "$cli" loft "$data" -q --holdout 2 "$@" | sed -n 's/^ *\([0-9][0-9]*\): \([^,]*\), \(.*\)/\1 \2 \3/p'; }
paste -d' ' <(per) <(per --guides "$tmp/edges.csv") |
  while read -r s a b _ c d; do echo "| $s | $a / $b | $c / $d |"; done
echo
echo "### Leave one out (12 lofted, 198 points measured; guides from all 13 sections)"
echo
echo "| withheld section | sections only max / rms [cm] | + LE and TE guides max / rms [cm] |"
echo "|---|---|---|"
for i in $(seq 1 11); do
  a=$(summary --withhold "$i" | sed 's/ | / \/ /')
  b=$(summary --withhold "$i" --guides "$tmp/edges.csv" | sed 's/ | / \/ /')
  echo "| $i | $a | $b |"
done
