#!/usr/bin/env bash
# Style and static checks: clang-format (no change needed), no line over 120 columns, and
# clang-tidy (.clang-tidy: bugprone, performance, function size) over every source file.
# Usage: scripts/lint.sh [--no-tidy]. Needs build/compile_commands.json (scripts/setup.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
status=0
mapfile -t files < <(git ls-files '*.cpp' '*.h')
if ! clang-format --dry-run -Werror "${files[@]}" 2>/tmp/gmg_format.log; then
  echo "lint: clang-format would change:"; grep -o '^[^:]*:[0-9]*' /tmp/gmg_format.log | sort -u | head -20
  status=1
fi
if awk 'length > 120 {print FILENAME ":" FNR ": " length " columns"; bad = 1} END {exit bad}' "${files[@]}"; then :; else
  status=1
fi
if [ "${1:-}" != "--no-tidy" ]; then
  mapfile -t sources < <(git ls-files '*.cpp' | grep -v '^tests/layering/')
  if ! run-clang-tidy -quiet -p build "${sources[@]}" > /tmp/gmg_tidy.log 2>&1; then status=1; fi
  if grep -E 'warning:|error:' /tmp/gmg_tidy.log; then status=1; fi
fi
[ $status -eq 0 ] && echo "lint: clean"
exit $status
