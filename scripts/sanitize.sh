#!/usr/bin/env bash
# The whole test suite built with AddressSanitizer and UndefinedBehaviorSanitizer, in build-asan/
# (clang when available, then the fuzz harnesses are built too; else gcc's sanitizers). Any
# memory error, leak or undefined behaviour fails the test that triggers it.
# Usage: scripts/sanitize.sh [extra ctest arguments]
set -euo pipefail
cd "$(dirname "$0")/.."
if command -v clang++ >/dev/null 2>&1; then
  compilers=(-DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++)
  fuzz=ON
else
  compilers=(-DCMAKE_C_COMPILER=gcc -DCMAKE_CXX_COMPILER=g++)
  fuzz=OFF
fi
jobs=$(nproc 2>/dev/null || echo 2)
# Warnings are the gcc build's gate (scripts/test.sh, -Werror); here they are shown, not fatal.
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Release "${compilers[@]}" -DGMG_SANITIZE=ON -DGMG_FUZZ="$fuzz" \
  -DGMG_BUILD_BENCHMARKS=OFF -DGMG_WERROR=OFF >/dev/null
cmake --build build-asan -j"$jobs"
# alloc_dealloc_mismatch=0: with clang, libstdc++ 12's std::stable_sort frees its temporary buffer
# in a way ASan reports as "operator new vs free" (inside <bits/stl_tempbuf.h>, not gmg's code).
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1:alloc_dealloc_mismatch=0}"
export LSAN_OPTIONS="${LSAN_OPTIONS:-suppressions=$PWD/scripts/lsan.supp:print_suppressions=0}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
cd build-asan
# The style and layering checks do not depend on the build, and the install test checks a
# Release install (this build carries debug information with source paths): scripts/test.sh
# runs them.
ctest --output-on-failure -j"$jobs" -E '^(Style|Layering|Install)\.' "$@"
