#!/usr/bin/env bash
# The whole test suite in the AddressSanitizer + UndefinedBehaviorSanitizer build (build-asan/,
# -O1 -g1 with assertions on; bench/ is not built). A memory error, a leak or undefined behaviour
# fails the test that ran into it. Prints CTest's summary; exits non-zero on any failure.
# .ci/run calls it after tools/test.sh (docs/reliability.md has the timings).
set -euo pipefail
# -g1: line tables only, enough for the sanitizers' stack traces (file:line); full -g made the
# instrumented objects 2-4x larger and took 42 % more compile time (docs/reliability.md section 4).
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${ASAN_BUILD_DIR:-$root/build-asan}
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g1" \
  -DINTERLIN_SANITIZE=ON -DINTERLIN_BUILD_TESTS=ON -DINTERLIN_BUILD_BENCH=OFF >/dev/null
cmake --build "$build" -j"$(nproc)"
cd "$build"
# halt_on_error: the first report ends the test; UBSan prints the stack of what it found.
export ASAN_OPTIONS=${ASAN_OPTIONS:-halt_on_error=1:detect_leaks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-halt_on_error=1:print_stacktrace=1}
ctest --output-on-failure -j"$(nproc)"
