#!/usr/bin/env bash
# Fuzzing: builds the libFuzzer targets of fuzz/ (all, or those named; clang,
# -fsanitize=fuzzer,address,undefined) in build-fuzz/ and runs each for SECONDS seconds, starting
# from its seed corpus (fuzz/corpus/NAME) and its past crashes (fuzz/regressions/NAME). Prints per
# target the executions and crashes, then "fuzz: N targets, E executions, C crashes"; exits 1 on any
# crash (the inputs are kept in build-fuzz/artifacts/NAME/: make each one a regression input before
# fixing it, docs/reliability.md). Run long sessions with `nice -n 19` on a shared machine.
# Usage: tools/fuzz.sh SECONDS [TARGET ...]     (default: all targets)
# Environment: FUZZ_BUILD_DIR (default build-fuzz), FUZZ_JOBS (build jobs, default all cores).
set -euo pipefail
seconds=${1:?usage: tools/fuzz.sh SECONDS [TARGET ...]}
shift
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${FUZZ_BUILD_DIR:-$root/build-fuzz}

# -O1 -g without NDEBUG: assertions (Eigen's index checks) stay on.
CC=clang CXX=clang++ cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g" \
  -DINTERLIN_FUZZ=ON -DINTERLIN_BUILD_TESTS=OFF -DINTERLIN_BUILD_BENCH=OFF >/dev/null

targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  for d in "$root"/fuzz/corpus/*/; do targets+=("$(basename "$d")"); done
fi
# Only the targets asked for (and what they link): a run of the CSV readers need not wait for PCL.
cmake --build "$build" -j"${FUZZ_JOBS:-$(nproc)}" --target "${targets[@]/#/fuzz_}" >/dev/null
total_execs=0
total_crashes=0
printf '%-14s %14s %8s\n' target executions crashes
for t in "${targets[@]}"; do
  work="$build/corpus/$t"     # inputs libFuzzer finds; the seeds in fuzz/ stay untouched
  artifacts="$build/artifacts/$t"
  log="$build/logs/$t.log"
  mkdir -p "$work" "$artifacts" "$(dirname "$log")"
  rm -f "$artifacts"/*
  dirs=("$work" "$root/fuzz/corpus/$t")
  [ -d "$root/fuzz/regressions/$t" ] && dirs+=("$root/fuzz/regressions/$t")
  dict=()
  [ -f "$root/fuzz/dict/$t.dict" ] && dict=("-dict=$root/fuzz/dict/$t.dict")
  # 2 GB per process and 10 s per input: more is a resource defect, reported as a crash.
  "$build/fuzz/fuzz_$t" "${dirs[@]}" "${dict[@]}" -max_total_time="$seconds" \
    -print_final_stats=1 -rss_limit_mb=2048 -timeout=10 -artifact_prefix="$artifacts/" \
    >"$log" 2>&1 || true
  execs=$(awk '/stat::number_of_executed_units:/ { n = $2 } END { print n + 0 }' "$log")
  crashes=$(find "$artifacts" -type f | wc -l)
  printf '%-14s %14d %8d\n' "$t" "$execs" "$crashes"
  if [ "$crashes" -gt 0 ]; then
    find "$artifacts" -type f -printf '  input: %p\n'
    grep -m1 -E 'ERROR|SUMMARY|unexpected exception' "$log" | sed 's/^/  /' || true
  fi
  total_execs=$((total_execs + execs))
  total_crashes=$((total_crashes + crashes))
done
echo "fuzz: ${#targets[@]} targets, $total_execs executions, $total_crashes crashes"
[ "$total_crashes" -eq 0 ]
