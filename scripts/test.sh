#!/usr/bin/env bash
# Sets up, builds and runs the whole test suite. Tests that need ../shared/data skip with a
# message when it is absent.
set -euo pipefail
cd "$(dirname "$0")/.."
# The same configuration as scripts/demo.sh's (warnings are errors in both), so after the demo
# only the tests are left to compile.
GMG_WERROR=ON bash scripts/setup.sh
jobs=$(nproc 2>/dev/null || echo 2)
cd build
ctest --output-on-failure -j"$jobs"
