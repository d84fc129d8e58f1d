#!/usr/bin/env bash
# scripts/slurm_batch.sh on a real Slurm: submits a batch of 5 test speeches against 2
# references as 3 parts plus the merge, waits for them, and checks that the parts' outputs are
# byte-identical to one local run's, that the merged folder holds them all, and that the merged
# summary covers every clip.
# Skips (exit 77) with a message when Slurm is not installed or no controller answers
# (scripts/setup_local_slurm.sh sets up a one-node cluster on this machine).
# Usage: slurm_batch_test.sh GMG_BINARY SOURCE_DIR
set -euo pipefail
gmg=$1 src=$2
if ! command -v sbatch >/dev/null || ! command -v sinfo >/dev/null; then
  echo "SKIP: Slurm is not installed (scripts/setup_local_slurm.sh installs a one-node cluster)"
  exit 77
fi
if ! sinfo -h -o '%T' 2>/dev/null | grep -qE '^(idle|mixed|allocated)'; then
  echo "SKIP: no Slurm controller or no usable node answers (start one with scripts/setup_local_slurm.sh)"
  exit 77
fi

work=$(mktemp -d /tmp/gmg_slurm_test.XXXXXX)
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/pool" "$work/tests"
"$gmg" synth -o "$work/pool" --stem ref_a --duration 10 --seed 21 >/dev/null
"$gmg" synth -o "$work/pool" --stem ref_b --duration 10 --seed 22 >/dev/null
for i in 1 2 3 4 5; do
  "$gmg" synth -o "$work/tests" --stem "t$i" --duration $((3 + i)) --seed $((30 + i)) --no-motion >/dev/null
done
options=(--pool "$work/pool" --tests "$work/tests" --seed 9 --reports)

GMG=$gmg "$src/scripts/slurm_batch.sh" submit 3 "$work/cluster" "${options[@]}"
for _ in $(seq 1 300); do
  [ -z "$(squeue -h -n gmg-batch,gmg-batch-merge -o %i 2>/dev/null)" ] && break
  sleep 1
done
if [ -n "$(squeue -h -n gmg-batch,gmg-batch-merge -o %i 2>/dev/null)" ]; then
  echo "FAIL: the jobs did not finish within 300 s"
  exit 1
fi
"$gmg" batch "${options[@]}" -o "$work/single" --progress none

status=0
for f in "$work"/single/*.bvh "$work"/single/t*.json; do
  name=$(basename "$f")
  found=("$work"/cluster/part-*/"$name")
  if [ ! -e "${found[0]}" ]; then
    echo "FAIL: $name is in no part"
    status=1
  elif ! cmp -s "$f" "${found[0]}"; then
    echo "FAIL: $name differs from the single run's"
    status=1
  fi
done
# The merge puts every part's outputs into the one folder, ready for what comes next.
for f in "$work"/single/*.bvh; do
  name=$(basename "$f")
  if ! cmp -s "$f" "$work/cluster/$name"; then
    echo "FAIL: the merged folder's $name is missing or differs from the single run's"
    status=1
  fi
done
if ! cmp -s "$work/single/pairs.csv" "$work/cluster/pairs.csv"; then
  echo "FAIL: the merged pairs.csv differs from the single run's"
  status=1
fi
if ! grep -q '"ok": 5' "$work/cluster/summary.json"; then
  echo "FAIL: the merged summary does not count 5 clips ok:"
  cat "$work/cluster/summary.json" "$work"/cluster/slurm-*.out 2>/dev/null | head -50
  status=1
fi
[ $status -eq 0 ] && echo "PASS: 3 Slurm parts and their merge equal one run"
exit $status
