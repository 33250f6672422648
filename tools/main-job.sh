#!/usr/bin/env bash
# README command 1: install what is missing, build, and run the main job on the bundled NASA
# Rotor 37 blade: 13 sections -> exact B-spline surface -> out/rotor37.{stl,igs,json,png}.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bash "$root/tools/setup.sh" build
bash "$root/tools/build.sh" -DINTERLIN_BUILD_TESTS=OFF -DINTERLIN_BUILD_BENCH=OFF
mkdir -p "$root/out"
cd "$root"
build/tools/interlin loft data/rotor37/sections.csv \
  -o out/rotor37.stl -o out/rotor37.igs -o out/rotor37.json -o out/rotor37.png \
  --units cm --cap --samples 400,120
