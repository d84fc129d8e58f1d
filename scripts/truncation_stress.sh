#!/usr/bin/env bash
# Truncates a graph file while `gmg reenact` reads it, RUNS times (default 200), at delays spread
# over the reenactment and to sizes spread over the file, and counts how each run ended: finished
# (the cut came after the graph was used), a one-line error naming the file (exit 1), or death by
# a signal (which must never happen). Exits 1 when any run died by a signal or ended otherwise.
#   bash scripts/truncation_stress.sh [RUNS] [path to gmg]
set -euo pipefail
runs=${1:-200}
gmg=${2:-build/gmg}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$gmg" synth -o "$work" --stem ref --duration 120 --seed 1 >/dev/null
"$gmg" synth -o "$work" --stem new --duration 30 --seed 2 --no-motion >/dev/null
"$gmg" build --motion "$work/ref.bvh" --audio "$work/ref.wav" --transcript "$work/ref.tsv" -o "$work/ref.gmg" \
  --progress none >/dev/null
size=$(stat -c %s "$work/ref.gmg")
# How long a reenactment takes here, so the cuts fall inside it.
start=$(date +%s%N)
"$gmg" reenact --graph "$work/ref.gmg" --audio "$work/new.wav" -o "$work/out.bvh" >/dev/null
span_ms=$((($(date +%s%N) - start) / 1000000 + 1))
finished=0 errors=0 signals=0 other=0
for ((i = 0; i < runs; i++)); do
  cp "$work/ref.gmg" "$work/cut.gmg"
  "$gmg" reenact --graph "$work/cut.gmg" --audio "$work/new.wav" -o "$work/cut.bvh" >/dev/null 2>"$work/err" &
  pid=$!
  delay_ms=$((i * span_ms / runs))
  sleep "$(awk -v ms="$delay_ms" 'BEGIN { printf "%.3f", ms / 1000 }')"
  truncate -s $(((i * 7919) % size)) "$work/cut.gmg"
  set +e
  wait "$pid"
  rc=$?
  set -e
  if ((rc == 0)); then
    finished=$((finished + 1))
  elif ((rc == 1)) && [ "$(wc -l <"$work/err")" -eq 1 ] && grep -q "^gmg: error: $work/cut.gmg: " "$work/err"; then
    errors=$((errors + 1))
  elif ((rc > 128)); then
    signals=$((signals + 1))
    echo "run $i: killed by signal $((rc - 128)) (cut to $(((i * 7919) % size)) bytes after ${delay_ms} ms)"
  else
    other=$((other + 1))
    echo "run $i: exit $rc: $(head -c 300 "$work/err")"
  fi
done
echo "truncation while reading: $runs runs (reenactment ${span_ms} ms, file $size bytes): $finished finished," \
  "$errors one-line errors, $signals killed by a signal, $other other"
((signals == 0 && other == 0))
