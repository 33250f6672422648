#!/usr/bin/env bash
# README command 2: install what is missing, build everything (library, CLI, tests, bench) and
# run the whole test suite with CTest. Prints CTest's summary; exits non-zero on any failure.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bash "$root/tools/setup.sh" build verify bench
bash "$root/tools/build.sh" -DINTERLIN_BUILD_TESTS=ON -DINTERLIN_BUILD_BENCH=ON
cd "${BUILD_DIR:-$root/build}"
ctest --output-on-failure -j"$(nproc)"
