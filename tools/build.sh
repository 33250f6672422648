#!/usr/bin/env bash
# Configures and builds interlin (Release, -O2) in build/ with all cores; extra arguments go to
# CMake's configure step (e.g. -DINTERLIN_SANITIZE=ON with a different BUILD_DIR).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${BUILD_DIR:-$root/build}
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
cmake --build "$build" -j"$(nproc)"
