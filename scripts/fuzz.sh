#!/usr/bin/env bash
# Builds the libFuzzer harnesses of tests/fuzz (clang, with ASan and UBSan, in build-asan/), writes
# their seed corpus (gmg_fuzz_seeds) and runs each harness for a fixed time. A crash, sanitizer
# report, timeout (10 s per input) or memory use above 2 GB fails; the input that did it is left in
# build-asan/fuzz/artifacts/. Without clang it says so and exits 0.
# Usage: scripts/fuzz.sh [seconds per harness, default 20]
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-20}"
if ! command -v clang++ >/dev/null 2>&1; then
  echo "fuzz: clang++ not found: the libFuzzer harnesses are skipped"
  exit 0
fi
jobs=$(nproc 2>/dev/null || echo 2)
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Release -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  -DGMG_SANITIZE=ON -DGMG_FUZZ=ON -DGMG_BUILD_BENCHMARKS=OFF -DGMG_WERROR=OFF >/dev/null
cmake --build build-asan -j"$jobs" --target gmg_fuzzers
work=build-asan/fuzz
rm -rf "$work/seeds"
mkdir -p "$work/artifacts" "$work/corpus"
build-asan/gmg_fuzz_seeds "$work/seeds"
# alloc_dealloc_mismatch=0: see scripts/sanitize.sh (libstdc++ std::stable_sort under clang).
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1:alloc_dealloc_mismatch=0}"
export LSAN_OPTIONS="${LSAN_OPTIONS:-suppressions=$PWD/scripts/lsan.supp:print_suppressions=0}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
status=0
for harness in build-asan/fuzz_*; do
  name=$(basename "$harness")
  target=${name#fuzz_}
  corpus="$work/corpus/$target"
  mkdir -p "$corpus"
  # The corpus grows from run to run in build-asan/; the seeds are read fresh each time.
  if "$harness" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=2048 -seed=1 \
      -print_final_stats=1 -artifact_prefix="$work/artifacts/$target-" "$corpus" "$work/seeds/$target" \
      >"$work/$target.log" 2>&1; then
    echo "fuzz: $target: ok ($(grep -m1 -o 'stat::number_of_executed_units: *[0-9]*' "$work/$target.log" |
      grep -o '[0-9]*$') runs in ${seconds}s)"
  else
    echo "fuzz: $target: FAILED (log: $work/$target.log)"
    tail -40 "$work/$target.log"
    status=1
  fi
done
exit $status
