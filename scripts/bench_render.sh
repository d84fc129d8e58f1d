#!/usr/bin/env bash
# Benchmark of `gmg render`: the whole command on a 60 s synthetic clip at 30 fps (1800 frames),
# 640x480, with its audio and captions, then the same beside a second motion (--compare,
# 1280x480). Prints the median, min and max wall time of several runs of each.
#   scripts/bench_render.sh [runs (default 5)] [path to gmg (default build/gmg)]
set -euo pipefail
cd "$(dirname "$0")/.."
runs=${1:-5}
gmg=${2:-build/gmg}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$gmg" synth -o "$work" --stem clip --duration 60 --seed 1 >/dev/null
"$gmg" synth -o "$work" --stem other --duration 60 --seed 2 >/dev/null

bench() {
  local name=$1
  shift
  local times=()
  for ((i = 0; i < runs; i++)); do
    local t0 t1
    t0=$(date +%s%N)
    "$gmg" render "$@" -o "$work/out.mp4" >/dev/null
    t1=$(date +%s%N)
    times+=("$(((t1 - t0) / 1000000))")
  done
  printf '%s\n' "${times[@]}" | sort -g | awk -v name="$name" -v runs="$runs" '
    { t[NR] = $1 / 1000 }
    END {
      median = (NR % 2) ? t[(NR + 1) / 2] : (t[NR / 2] + t[NR / 2 + 1]) / 2
      printf "%-34s runs %d  median %6.2f s  min %6.2f s  max %6.2f s\n", name, runs, median, t[1], t[NR]
    }'
}

echo "gmg render, 60 s at 30 fps (1800 frames), $(nproc) cores"
bench "640x480, audio, captions" "$work/clip.bvh" --audio "$work/clip.wav" --transcript "$work/clip.tsv"
bench "1280x480 --compare, audio, captions" "$work/clip.bvh" --audio "$work/clip.wav" --transcript "$work/clip.tsv" \
  --compare "$work/other.bvh"
