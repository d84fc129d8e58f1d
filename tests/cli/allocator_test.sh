#!/usr/bin/env bash
# The gmg command runs on jemalloc with transparent huge pages asked for (engine/cli/main.cpp):
# jemalloc prints its settings at exit with MALLOC_CONF=stats_print:true, and the command's own
# setting must be among them. Fails when the command is linked without jemalloc (nothing printed),
# or when jemalloc does not read the command's setting (thp would be "default").
set -uo pipefail
gmg=$1
out=$(MALLOC_CONF=stats_print:true "$gmg" --version 2>&1)
if ! grep -q 'jemalloc' <<<"$out"; then
  echo "FAIL: $gmg printed no jemalloc statistics (not linked with jemalloc?)"
  exit 1
fi
if ! grep -q 'opt.thp: "always"' <<<"$out"; then
  echo "FAIL: jemalloc runs without the command's setting: $(grep 'opt.thp' <<<"$out")"
  exit 1
fi
if ! grep -q '^gmg ' <<<"$out"; then
  echo "FAIL: --version printed no version"
  exit 1
fi
echo "PASS: $(grep -m1 -i 'version' <<<"$out" | sed 's/^ *//'), opt.thp always"
