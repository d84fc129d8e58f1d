#!/usr/bin/env bash
#SBATCH --job-name=gmg-batch
#SBATCH --cpus-per-task=2
# `gmg batch` on a Slurm cluster: a job array whose task K of N runs part K/N of the batch
# (gmg batch --shard K/N) into OUTDIR/part-K, and a job that joins the parts' summaries
# (gmg batch --merge) into OUTDIR once every part has ended. The parts write exactly what one
# run of the whole batch would (see `gmg batch --help`).
#
#   scripts/slurm_batch.sh submit N OUTDIR [gmg batch options...]
#       submits both: the array of N parts and the merge (run this on a login node)
#   sbatch --array=1-N scripts/slurm_batch.sh OUTDIR [gmg batch options...]
#       only the parts; join them later with: gmg batch --merge OUTDIR/part-* -o OUTDIR
#
# The batch options are those of `gmg batch` (--pool/--graph, --tests, --seed, --reports, ...),
# with paths every node can read. Each part uses its task's CPUs (--cpus-per-task, 2 by default:
# override with sbatch options, e.g. SBATCH_CPUS_PER_TASK=8). GMG names the gmg binary (default:
# gmg on the PATH); SBATCH_* environment variables pass further sbatch options (partition,
# time, memory: a part holds about one reference graph per CPU).
set -euo pipefail
gmg=${GMG:-gmg}

if [ "${1:-}" = submit ]; then
  if [ $# -lt 3 ]; then
    echo "usage: $0 submit N OUTDIR [gmg batch options...]" >&2
    exit 2
  fi
  n=$2 out=$3
  shift 3
  mkdir -p "$out"
  out=$(cd "$out" && pwd)
  parts=()
  for k in $(seq 1 "$n"); do parts+=("$out/part-$k"); done
  array=$(sbatch --parsable --array=1-"$n" --output="$out/slurm-%A_%a.out" --export=ALL,GMG="$gmg" \
    "$0" "$out" "$@")
  merge=$(sbatch --parsable --job-name=gmg-batch-merge --cpus-per-task=1 --dependency=afterany:"${array%%;*}" \
    --output="$out/slurm-%j-merge.out" --wrap "$(printf '%q ' "$gmg" batch --merge "${parts[@]}" -o "$out")")
  echo "slurm_batch: parts in job array ${array%%;*} (1-$n), merge in job ${merge%%;*}; results in $out"
  exit 0
fi

if [ -z "${SLURM_ARRAY_TASK_ID:-}" ] || [ $# -lt 1 ]; then
  echo "usage: sbatch --array=1-N $0 OUTDIR [gmg batch options...]  (or: $0 submit N OUTDIR ...)" >&2
  exit 2
fi
out=$1
shift
k=$((SLURM_ARRAY_TASK_ID - ${SLURM_ARRAY_TASK_MIN:-1} + 1))
n=${SLURM_ARRAY_TASK_COUNT:?not a job array task}
exec "$gmg" batch --shard "$k/$n" -o "$out/part-$k" --jobs "${SLURM_CPUS_PER_TASK:-0}" --progress lines "$@"
