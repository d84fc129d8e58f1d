#!/usr/bin/env bash
# Sets up, builds and runs the whole test suite. Tests that need ../shared/data skip with a
# message when it is absent.
set -euo pipefail
cd "$(dirname "$0")/.."
GMG_WERROR=ON bash scripts/setup.sh
jobs=$(nproc 2>/dev/null || echo 2)
cd build
ctest --output-on-failure -j"$jobs"
